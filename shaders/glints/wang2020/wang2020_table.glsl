// The frame of the prefiltered 4D glint table (Wang et al. 2020, Sec. 4.2), shared by the prefilter pass
// (glints/wang2020/wang2020_prefilter.comp) and its lookup (ibl/wang2020.glsl): world normal from (theta_n, phi_n) about +y,
// x = d n / d theta, y = n x x (defined at the poles too, through phi_n).
mat3 wang2020Frame(float thetaN, float phiN) {
    vec3 n = vec3(sin(thetaN) * cos(phiN), cos(thetaN), sin(thetaN) * sin(phiN));
    vec3 x = vec3(cos(thetaN) * cos(phiN), -sin(thetaN), cos(thetaN) * sin(phiN));
    return mat3(x, cross(n, x), n);
}
