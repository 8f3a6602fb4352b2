// The pixel footprint in UV space: the ellipse spanned by duv/dx and duv/dy. Its axes come from the
// eigen-decomposition of J J^T with J = [duv/dx duv/dy] (the ellipse's quadratic form is (J J^T)^-1).
struct FootprintEllipse {
    vec2 majorDir;     // unit direction of the major axis in UV
    float major;       // semi-axis lengths in UV units (>= minor > 0)
    float minor;
};

FootprintEllipse footprintEllipse(vec2 duvdx, vec2 duvdy) {
    // Covariance-like matrix S = J J^T = [a b; b c].
    float a = duvdx.x * duvdx.x + duvdy.x * duvdy.x;
    float b = duvdx.x * duvdx.y + duvdy.x * duvdy.y;
    float c = duvdx.y * duvdx.y + duvdy.y * duvdy.y;
    float mean = 0.5 * (a + c);
    float diff = 0.5 * (a - c);
    float root = sqrt(diff * diff + b * b);
    float l1 = mean + root;
    FootprintEllipse e;
    e.major = sqrt(max(l1, 1e-24));
    // The minor axis from the determinant (major x minor = |det J|) rather than sqrt(mean - root): the difference
    // cancels catastrophically in float for the very elongated footprints of grazing views.
    float detJ = abs(duvdx.x * duvdy.y - duvdx.y * duvdy.x);
    e.minor = clamp(detJ / e.major, 1e-12, e.major);
    vec2 dir = abs(b) > 1e-30 ? vec2(l1 - c, b) : (a >= c ? vec2(1.0, 0.0) : vec2(0.0, 1.0));
    e.majorDir = normalize(dir);
    return e;
}
