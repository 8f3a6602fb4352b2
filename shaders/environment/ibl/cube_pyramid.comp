// One level of a cube-map MIP pyramid (Sec. 3 of "Real-time Rendering of Glossy Materials with Regular Sampling",
// CGI 2014, Table 1): destination texel i of level L+1 is the weighted mean of a K x K block of level L centred on
// its 2 x 2 parents, with separable binomial weights: K = 2 box [1 1]/2, K = 4 Gaussian [1 3 3 1]/8, K = 6 Gaussian
// [1 5 10 10 5 1]/32 (the "pyramids of Gaussians" of Adelson 1981 with 4x4 and 6x6 kernels).
// Deviation: taps outside the face are clamped to the face edge (no filtering across cube faces).
// CPU reference: engine/environment/ibl/cube_pyramid.cpp downsampleCubeFaceReference.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
#ifndef PYRAMID_FORMAT
#define PYRAMID_FORMAT rgba16f
#endif
layout(binding = 0, PYRAMID_FORMAT) uniform readonly imageCube u_source;
layout(binding = 1, PYRAMID_FORMAT) uniform writeonly imageCube u_destination;
layout(location = 0) uniform int u_kernel;   // 2, 4 or 6

float tapWeight(int k) {
    if (u_kernel == 4) return (k == 0 || k == 3) ? 1.0 / 8.0 : 3.0 / 8.0;
    if (u_kernel == 6) return k == 0 || k == 5 ? 1.0 / 32.0 : (k == 1 || k == 4 ? 5.0 / 32.0 : 10.0 / 32.0);
    return 0.5;
}

void main() {
    ivec2 destSize = imageSize(u_destination).xy;
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= destSize.x || id.y >= destSize.y) return;
    int sourceSize = imageSize(u_source).x;
    int first = 1 - u_kernel / 2;   // block offset relative to the parent 2i
    vec4 sum = vec4(0.0);
    for (int ky = 0; ky < u_kernel; ++ky) {
        int y = clamp(2 * id.y + first + ky, 0, sourceSize - 1);
        float wy = tapWeight(ky);
        for (int kx = 0; kx < u_kernel; ++kx) {
            int x = clamp(2 * id.x + first + kx, 0, sourceSize - 1);
            sum += (wy * tapWeight(kx)) * imageLoad(u_source, ivec3(x, y, id.z));
        }
    }
    imageStore(u_destination, id, sum);
}
