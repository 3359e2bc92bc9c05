// ecc_runtime.hpp — the eigensystem runtime of ecc, in C++17 (header only).
//
// Shipped with the ecc code generator (`ecc FILE.psi --emit cpp` inlines it
// into every emitted header, behind the include guard below, so one emitted
// header is self-contained and several can be included together). It is a
// line-by-line port of the Rust crate ecc-runtime (runtime/core/src) with the
// same conventions, so results agree with the Rust runtime to rounding:
//
//   * signed SVD F = U diag(σ) Vᵀ with U, V ∈ SO(d), |σ0| ≥ |σ1| ≥ |σ2| and
//     only the last σ possibly negative (svd/two.rs: closed form; svd/three.rs:
//     analytic eigenvectors of FᵀF + Gram–Schmidt QR of F V);
//   * the Hessian ∂²Ψ/∂f² = Σ_ij A_ij d_i d_jᵀ + Σ_pairs λ_t t tᵀ + λ_l l lᵀ
//     (Smith et al. 2019 eqs. 22–23, Zhu 2020 eq. 28) with scaling modes
//     d_i = vec(u_i v_iᵀ), twist t = vec(u_j v_iᵀ − u_i v_jᵀ)/√2 and flip
//     l = vec(u_j v_iᵀ + u_i v_jᵀ)/√2; pair slots 3D k=0→(1,2), 1→(2,0),
//     2→(0,1), 2D k=0→(0,1) (spectral.rs);
//   * filters None (raw), Clamp (max(λ,0)), ClampEps(ε) (max(λ,ε)), Abs (|λ|);
//     a non-finite λ is mapped to the floor by all but None (filter.rs);
//   * the scaling block is filtered without an eigensolve when no eigenvalue
//     is below the floor (LDLᵀ inertia), else with at most one eigenpair
//     (assemble.rs);
//   * vec is column-major: vec(F)[c·d + r] = F_rc; element vectors are
//     node-major [x0.x, x0.y, (x0.z), x1.x, …] and every element quantity is
//     multiplied by the rest measure (element/eval.rs);
//   * fibre energies ψ(I4, I5) of a unit rest direction a (fibre.rs,
//     fibre/*.rs): I4, I5, ∂ψ/∂F and the filtered Hessian, closed form
//     (eqs. P3–P5) when ψ has no I4 derivative, else a d²×d² Jacobi
//     eigensolve of the analytic Hessian (eq. P2 with F5); see "fibres" below.
//
// Standard library only (<cmath>, <cstdint>, <limits>), fixed-size arrays, no
// allocation, no exceptions, no virtual calls. For CUDA/HIP, define
//
//     #define ECC_HOST_DEVICE __host__ __device__
//
// before including an emitted header: every function is marked with it.
// Matrices are `double m[row][col]`.
#ifndef ECC_RUNTIME_HPP
#define ECC_RUNTIME_HPP

#include <cmath>
#include <cstdint>
#include <limits>

#ifndef ECC_HOST_DEVICE
#define ECC_HOST_DEVICE
#endif

namespace ecc {

/// Relative switch threshold τ = ε^{1/3} between a divided difference and
/// its limit form (divided.rs: either branch is accurate to ≈ ε^{2/3}).
constexpr double LIMIT_TOL = 6.055454452393343e-6;

constexpr double FRAC_1_SQRT_2 = 0.70710678118654752440;
/// f64::EPSILON (a literal, so device code needs no host constexpr call).
constexpr double EPS = 2.220446049250313e-16;
static_assert(EPS == std::numeric_limits<double>::epsilon(), "IEEE double expected");

/// +∞ and NaN through the <cmath> macros (usable in host and device code).
ECC_HOST_DEVICE inline double infinity() { return HUGE_VAL; }
ECC_HOST_DEVICE inline double nan() { return NAN; }
/// Rust's f64::max / f64::min: a NaN operand is ignored.
ECC_HOST_DEVICE inline double fmax(double a, double b) { return std::fmax(a, b); }
/// Ψ as energies report it: a non-finite value (outside the domain) is +∞.
ECC_HOST_DEVICE inline double finite_or_inf(double x) { return std::isfinite(x) ? x : infinity(); }
/// Rust's f64::clamp (a NaN stays NaN).
ECC_HOST_DEVICE inline double clamp(double x, double lo, double hi) {
    return x < lo ? lo : (x > hi ? hi : x);
}

// ---------------------------------------------------------------- filters

/// How eigenvalues are made non-negative (filter.rs).
enum class FilterKind { None, Clamp, ClampEps, Abs };

/// A filter: the kind and, for ClampEps, ε.
struct Filter {
    FilterKind kind = FilterKind::Clamp;
    double eps = 0.0;

    ECC_HOST_DEVICE static Filter none() { return Filter{FilterKind::None, 0.0}; }
    ECC_HOST_DEVICE static Filter clamp() { return Filter{FilterKind::Clamp, 0.0}; }
    ECC_HOST_DEVICE static Filter clamp_eps(double e) { return Filter{FilterKind::ClampEps, e}; }
    ECC_HOST_DEVICE static Filter abs() { return Filter{FilterKind::Abs, 0.0}; }

    /// The smallest value the filter outputs (ε for a meaningful ClampEps, else 0).
    ECC_HOST_DEVICE double floor() const {
        return (kind == FilterKind::ClampEps && std::isfinite(eps) && eps > 0.0) ? eps : 0.0;
    }
    ECC_HOST_DEVICE bool is_raw() const { return kind == FilterKind::None; }
    /// The filtered eigenvalue.
    ECC_HOST_DEVICE double apply(double lambda) const {
        if (kind == FilterKind::None) return lambda;
        if (!std::isfinite(lambda)) return floor();
        switch (kind) {
        case FilterKind::Clamp: return ecc::fmax(lambda, 0.0);
        case FilterKind::ClampEps: return ecc::fmax(lambda, floor());
        default: return std::fabs(lambda);
        }
    }
};

// ------------------------------------------------------- spectral data

/// Ψ and its stretch-space derivatives at one point (spectral.rs): Ψ,
/// ∂Ψ/∂σ, the scaling block A = ∂²Ψ/∂σ² (`diagonal`: the CAS proved the
/// off-diagonals vanish, only scale[i][i] is meaningful) and the twist/flip
/// eigenvalue of each pair slot (2D: slot 0 only).
template <int D>
struct Spectral {
    double psi;
    double grad[D];
    bool diagonal;
    double scale[D][D];
    double twist[3];
    double flip[3];

    /// Outside the domain: Ψ = +∞, every derivative 0.
    ECC_HOST_DEVICE static Spectral infinite() {
        Spectral s{};
        s.psi = infinity();
        s.diagonal = true;
        return s;
    }
};

// ------------------------------------------------- small symmetric eigen

namespace detail {

ECC_HOST_DEVICE inline double dot3(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

ECC_HOST_DEVICE inline void cross3(const double a[3], const double b[3], double out[3]) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

ECC_HOST_DEVICE inline void copy3(const double a[3], double out[3]) {
    out[0] = a[0];
    out[1] = a[1];
    out[2] = a[2];
}

ECC_HOST_DEVICE inline void swap_d(double& a, double& b) {
    double t = a;
    a = b;
    b = t;
}

ECC_HOST_DEVICE inline void swap3(double a[3], double b[3]) {
    for (int k = 0; k < 3; ++k) swap_d(a[k], b[k]);
}

/// Eigenvalues (descending) and vectors (rows, a rotation) of [[a, b], [b, c]]
/// with entries of order 1 (sym.rs `sym2_eigen_scaled`).
ECC_HOST_DEVICE inline void sym2_eigen_scaled(double a, double b, double c, double vals[2],
                                              double vecs[2][2]) {
    double m = 0.5 * (a + c);
    double h = 0.5 * (a - c);
    double r = std::sqrt(h * h + b * b);
    if (r == 0.0) {
        vals[0] = a;
        vals[1] = c;
        vecs[0][0] = 1.0; vecs[0][1] = 0.0;
        vecs[1][0] = 0.0; vecs[1][1] = 1.0;
        return;
    }
    double x = h >= 0.0 ? h + r : b;
    double y = h >= 0.0 ? b : r - h;
    double n = 1.0 / std::sqrt(x * x + y * y);
    double cs = x * n, sn = y * n;
    vals[0] = m + r;
    vals[1] = m - r;
    vecs[0][0] = cs; vecs[0][1] = sn;
    vecs[1][0] = -sn; vecs[1][1] = cs;
}

/// sym.rs `sym2_eigen`: any finite symmetric 2×2.
ECC_HOST_DEVICE inline void sym2_eigen(double a, double b, double c, double vals[2],
                                       double vecs[2][2]) {
    vecs[0][0] = 1.0; vecs[0][1] = 0.0;
    vecs[1][0] = 0.0; vecs[1][1] = 1.0;
    if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(c))) {
        vals[0] = vals[1] = nan();
        return;
    }
    double scale = ecc::fmax(ecc::fmax(std::fabs(a), std::fabs(b)), std::fabs(c));
    if (scale == 0.0) {
        vals[0] = vals[1] = 0.0;
        return;
    }
    double inv = 1.0 / scale;
    sym2_eigen_scaled(a * inv, b * inv, c * inv, vals, vecs);
    vals[0] *= scale;
    vals[1] *= scale;
}

/// cos(acos(t)/3) for t ∈ [0, 1]: degree-5 fit + one Halley step (sym.rs `trisect`).
ECC_HOST_DEVICE inline double trisect(double t) {
    double c = 0.8660260610588331 +
               t * (0.1666188565150354 +
                    t * (-0.04752501393243526 +
                         t * (0.021899627345145625 +
                              t * (-0.008966451200158584 + t * 0.0019473016104169356))));
    double g = c * (4.0 * c * c - 3.0) - t;
    double g1 = 12.0 * c * c - 3.0;
    return c - 2.0 * g * g1 / (2.0 * g1 * g1 - g * 24.0 * c);
}

/// The best-separated eigenpair of an order-1 symmetric 3×3 (sym.rs `Isolated`).
struct Isolated {
    double value;
    double vector[3];
    bool is_max;
};

/// sym.rs `isolated_scaled`; false when all eigenvalues are equal to rounding.
ECC_HOST_DEVICE inline bool isolated_scaled(const double a[3][3], Isolated& out) {
    double q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    double p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    double d[3] = {a[0][0] - q, a[1][1] - q, a[2][2] - q};
    double p2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2.0 * p1;
    double p = std::sqrt(p2 / 6.0);
    if (!(p > 4.0 * EPS)) return false;
    double ip = 1.0 / p;
    double b00 = d[0] * ip, b11 = d[1] * ip, b22 = d[2] * ip;
    double b01 = a[0][1] * ip, b02 = a[0][2] * ip, b12 = a[1][2] * ip;
    double det_b = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02) +
                   b02 * (b01 * b12 - b11 * b02);
    double r = clamp(0.5 * det_b, -1.0, 1.0);
    double c = trisect(std::fabs(r));
    bool is_max = r >= 0.0;
    double iso = is_max ? q + 2.0 * p * c : q - 2.0 * p * c;
    double r0[3] = {a[0][0] - iso, a[0][1], a[0][2]};
    double r1[3] = {a[0][1], a[1][1] - iso, a[1][2]};
    double r2[3] = {a[0][2], a[1][2], a[2][2] - iso};
    double cr[3][3];
    cross3(r0, r1, cr[0]);
    cross3(r0, r2, cr[1]);
    cross3(r1, r2, cr[2]);
    double n[3] = {dot3(cr[0], cr[0]), dot3(cr[1], cr[1]), dot3(cr[2], cr[2])};
    int k = (n[0] >= n[1] && n[0] >= n[2]) ? 0 : (n[1] >= n[2] ? 1 : 2);
    if (std::isnan(n[k]) || n[k] <= 0.0) return false;
    double inv_n = 1.0 / std::sqrt(n[k]);
    for (int i = 0; i < 3; ++i) out.vector[i] = cr[k][i] * inv_n;
    double av[3] = {dot3(a[0], out.vector), dot3(a[1], out.vector), dot3(a[2], out.vector)};
    out.value = dot3(out.vector, av);
    out.is_max = is_max;
    return true;
}

/// Sort eigenpairs descending and make the basis a rotation (sym.rs `sorted`).
ECC_HOST_DEVICE inline void sorted(double vals[3], double vecs[3][3]) {
    if (vals[0] < vals[1]) { swap_d(vals[0], vals[1]); swap3(vecs[0], vecs[1]); }
    if (vals[1] < vals[2]) { swap_d(vals[1], vals[2]); swap3(vecs[1], vecs[2]); }
    if (vals[0] < vals[1]) { swap_d(vals[0], vals[1]); swap3(vecs[0], vecs[1]); }
    double c[3];
    cross3(vecs[0], vecs[1], c);
    if (dot3(c, vecs[2]) < 0.0)
        for (int k = 0; k < 3; ++k) vecs[2][k] = -vecs[2][k];
}

/// sym.rs `complete_scaled`: the full decomposition from the isolated pair
/// (`iso` null: all eigenvalues equal, the diagonal with the identity basis).
ECC_HOST_DEVICE inline void complete_scaled(const double a[3][3], const Isolated* iso,
                                            double vals[3], double vecs[3][3]) {
    if (iso == nullptr) {
        for (int i = 0; i < 3; ++i) {
            vals[i] = a[i][i];
            for (int j = 0; j < 3; ++j) vecs[i][j] = i == j ? 1.0 : 0.0;
        }
        sorted(vals, vecs);
        return;
    }
    const double* v0 = iso->vector;
    double l0 = iso->value;
    double sign = std::copysign(1.0, v0[2]);
    double ia = -1.0 / (sign + v0[2]);
    double bb = v0[0] * v0[1] * ia;
    double w1[3] = {1.0 + sign * v0[0] * v0[0] * ia, sign * bb, -sign * v0[0]};
    double w2[3] = {bb, sign + v0[1] * v0[1] * ia, -v0[1]};
    double aw1[3] = {dot3(a[0], w1), dot3(a[1], w1), dot3(a[2], w1)};
    double aw2[3] = {dot3(a[0], w2), dot3(a[1], w2), dot3(a[2], w2)};
    double ev[2], evec[2][2];
    sym2_eigen_scaled(dot3(w1, aw1), dot3(w1, aw2), dot3(w2, aw2), ev, evec);
    double y1[3], y2[3];
    for (int k = 0; k < 3; ++k) {
        y1[k] = evec[0][0] * w1[k] + evec[0][1] * w2[k];
        y2[k] = evec[1][0] * w1[k] + evec[1][1] * w2[k];
    }
    if (!iso->is_max) {
        vals[0] = ev[0]; vals[1] = ev[1]; vals[2] = l0;
        copy3(y1, vecs[0]); copy3(y2, vecs[1]); copy3(v0, vecs[2]);
    } else {
        vals[0] = l0; vals[1] = ev[0]; vals[2] = ev[1];
        copy3(v0, vecs[0]); copy3(y1, vecs[1]); copy3(y2, vecs[2]);
    }
}

/// sym.rs `sym3_eigen_scaled`.
ECC_HOST_DEVICE inline void sym3_eigen_scaled(const double a[3][3], double vals[3],
                                              double vecs[3][3]) {
    Isolated iso;
    bool ok = isolated_scaled(a, iso);
    complete_scaled(a, ok ? &iso : nullptr, vals, vecs);
}

/// sym.rs `sym3_eigen`: values descending, vecs[k] the unit vector of vals[k].
ECC_HOST_DEVICE inline void sym3_eigen(const double m[3][3], double vals[3], double vecs[3][3]) {
    double s[6] = {m[0][0], m[1][1], m[2][2], m[0][1], m[0][2], m[1][2]};
    double scale = 0.0;
    bool has_nan = false;
    for (double x : s) {
        scale = ecc::fmax(scale, std::fabs(x));
        has_nan = has_nan || std::isnan(x);
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) vecs[i][j] = i == j ? 1.0 : 0.0;
    if (!std::isfinite(scale) || has_nan) {
        vals[0] = vals[1] = vals[2] = nan();
        return;
    }
    if (scale == 0.0) {
        vals[0] = vals[1] = vals[2] = 0.0;
        return;
    }
    double inv = 1.0 / scale;
    double a[3][3] = {{s[0] * inv, s[3] * inv, s[4] * inv},
                      {s[3] * inv, s[1] * inv, s[5] * inv},
                      {s[4] * inv, s[5] * inv, s[2] * inv}};
    sym3_eigen_scaled(a, vals, vecs);
    for (int k = 0; k < 3; ++k) vals[k] *= scale;
    sorted(vals, vecs);
}

/// sym.rs `normalised`: m / max|m_ij|; false for a zero or non-finite matrix.
ECC_HOST_DEVICE inline bool normalised(const double m[3][3], double out[3][3], double& scale) {
    scale = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) scale = ecc::fmax(scale, std::fabs(m[i][j]));
    if (!std::isfinite(scale) || scale == 0.0) return false;
    double inv = 1.0 / scale;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out[i][j] = m[i][j] * inv;
    return true;
}

}  // namespace detail

// ------------------------------------------------------------ signed SVD

/// F = U diag(σ) Vᵀ, U, V ∈ SO(D) (u[r][c]: column c is u_c).
template <int D>
struct Svd {
    double u[D][D];
    double sigma[D];
    double v[D][D];

    ECC_HOST_DEVICE bool is_finite() const {
        for (int i = 0; i < D; ++i) {
            if (!std::isfinite(sigma[i])) return false;
            for (int j = 0; j < D; ++j)
                if (!std::isfinite(u[i][j]) || !std::isfinite(v[i][j])) return false;
        }
        return true;
    }
};

namespace detail {
template <int D>
ECC_HOST_DEVICE inline void set_identity(double m[D][D]) {
    for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) m[i][j] = i == j ? 1.0 : 0.0;
}

template <int D>
ECC_HOST_DEVICE inline Svd<D> svd_non_finite() {
    Svd<D> s;
    set_identity<D>(s.u);
    set_identity<D>(s.v);
    for (int i = 0; i < D; ++i) s.sigma[i] = nan();
    return s;
}
}  // namespace detail

/// Closed-form signed SVD of a 2×2 (svd/two.rs): F = Q·rot(α₂) + R·refl(α₁).
ECC_HOST_DEVICE inline Svd<2> signed_svd2(const double f[2][2]) {
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            if (!std::isfinite(f[i][j])) return detail::svd_non_finite<2>();
    double a = f[0][0], b = f[0][1], c = f[1][0], d = f[1][1];
    double e = 0.5 * (a + d), h = 0.5 * (c - b), p = 0.5 * (a - d), g = 0.5 * (c + b);
    double q = std::hypot(e, h), r = std::hypot(p, g);
    double a2 = std::atan2(h, e), a1 = std::atan2(g, p);
    double phi = 0.5 * (a1 + a2), psi = 0.5 * (a1 - a2);
    double sphi = std::sin(phi), cphi = std::cos(phi);
    double spsi = std::sin(psi), cpsi = std::cos(psi);
    Svd<2> s;
    s.u[0][0] = cphi; s.u[0][1] = -sphi; s.u[1][0] = sphi; s.u[1][1] = cphi;
    s.sigma[0] = q + r;
    s.sigma[1] = q - r;
    s.v[0][0] = cpsi; s.v[0][1] = -spsi; s.v[1][0] = spsi; s.v[1][1] = cpsi;
    return s;
}

namespace detail {

/// Unit vector along b − (u·b)u, re-orthogonalised once when cancellation is
/// severe; any unit vector ⟂ u at rank ≤ 1 (svd/three.rs `orthonormal_against`).
ECC_HOST_DEVICE inline void orthonormal_against(const double u[3], const double b[3], double r00,
                                                double out[3]) {
    double c = dot3(u, b);
    double r[3] = {b[0] - c * u[0], b[1] - c * u[1], b[2] - c * u[2]};
    double n2 = dot3(r, r);
    if (n2 <= 1e-8 * dot3(b, b)) {
        double c2 = dot3(u, r);
        for (int k = 0; k < 3; ++k) r[k] = r[k] - c2 * u[k];
        n2 = dot3(r, r);
        if (std::isnan(n2) || n2 <= (EPS * EPS) * r00 * r00) {
            double w[3];
            if (std::fabs(u[0]) > std::fabs(u[1])) {
                w[0] = -u[2]; w[1] = 0.0; w[2] = u[0];
            } else {
                w[0] = 0.0; w[1] = u[2]; w[2] = -u[1];
            }
            double s = 1.0 / std::sqrt(dot3(w, w));
            for (int k = 0; k < 3; ++k) out[k] = w[k] * s;
            return;
        }
    }
    double s = 1.0 / std::sqrt(n2);
    for (int k = 0; k < 3; ++k) out[k] = r[k] * s;
}

/// |σ0| ≥ |σ1| ≥ |σ2|, negative sign only in σ2, det U = det V = +1
/// (svd/three.rs `fix_order`; u, v hold columns).
ECC_HOST_DEVICE inline void fix_order(double sigma[3], double u[3][3], double v[3][3]) {
    auto swap = [&](int i, int j) {
        swap_d(sigma[i], sigma[j]);
        swap3(u[i], u[j]);
        swap3(v[i], v[j]);
        for (int k = 0; k < 3; ++k) {
            u[i][k] = -u[i][k];
            v[i][k] = -v[i][k];
        }
    };
    if (std::fabs(sigma[0]) < std::fabs(sigma[1])) swap(0, 1);
    if (std::fabs(sigma[1]) < std::fabs(sigma[2])) swap(1, 2);
    if (std::fabs(sigma[0]) < std::fabs(sigma[1])) swap(0, 1);
    for (int i = 0; i < 2; ++i) {
        if (sigma[i] < 0.0) {
            sigma[i] = -sigma[i];
            sigma[2] = -sigma[2];
            for (int k = 0; k < 3; ++k) {
                u[i][k] = -u[i][k];
                u[2][k] = -u[2][k];
            }
        }
    }
}

/// The trailing block [[R11, R12], [0, R22]] by its own signed SVD, folded
/// into columns 1, 2 of U and V (svd/three.rs `trailing_2x2`).
ECC_HOST_DEVICE inline void trailing_2x2(double r11, double r12, double r22, double sigma[3],
                                         double u[3][3], double v[3][3]) {
    const double blk[2][2] = {{r11, r12}, {0.0, r22}};
    Svd<2> s2 = signed_svd2(blk);
    auto mix = [](double cols[3][3], const double r[2][2]) {
        double c1[3], c2[3];
        copy3(cols[1], c1);
        copy3(cols[2], c2);
        for (int k = 0; k < 3; ++k) {
            cols[1][k] = c1[k] * r[0][0] + c2[k] * r[1][0];
            cols[2][k] = c1[k] * r[0][1] + c2[k] * r[1][1];
        }
    };
    mix(u, s2.u);
    mix(v, s2.v);
    sigma[1] = s2.sigma[0];
    sigma[2] = s2.sigma[1];
}

/// Two powers of two whose product brings `big` into [1, 2) (exact scaling).
ECC_HOST_DEVICE inline void pow2_scale(double big, double& s1, double& s2) {
    int e2 = 0;
    (void)std::frexp(big, &e2);  // big = m·2^e2, m ∈ [0.5, 1)
    int e = e2 - 1;
    int half = e / 2;
    s1 = std::ldexp(1.0, -half);
    s2 = std::ldexp(1.0, half - e);
}

}  // namespace detail

/// Signed SVD of a 3×3 (svd/three.rs): V from the eigenvectors of FᵀF, then
/// Gram–Schmidt QR of F V with U = [u0, u1, u0 × u1] and σ = diag(R).
ECC_HOST_DEVICE inline Svd<3> signed_svd3(const double f[3][3]) {
    using namespace detail;
    double fm[3][3];
    double big = 0.0;
    bool has_nan = false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            fm[i][j] = f[i][j];
            big = ecc::fmax(big, std::fabs(f[i][j]));
            has_nan = has_nan || std::isnan(f[i][j]);
        }
    if (!std::isfinite(big) || has_nan) return svd_non_finite<3>();
    Svd<3> out;
    if (big == 0.0) {
        set_identity<3>(out.u);
        set_identity<3>(out.v);
        out.sigma[0] = out.sigma[1] = out.sigma[2] = 0.0;
        return out;
    }
    double s1, s2;
    pow2_scale(big, s1, s2);
    for (auto& row : fm)
        for (double& x : row) x = x * s1 * s2;
    double c[3][3];  // columns of F
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) c[j][i] = fm[i][j];
    const double ftf[3][3] = {{dot3(c[0], c[0]), dot3(c[0], c[1]), dot3(c[0], c[2])},
                              {dot3(c[0], c[1]), dot3(c[1], c[1]), dot3(c[1], c[2])},
                              {dot3(c[0], c[2]), dot3(c[1], c[2]), dot3(c[2], c[2])}};
    double evals[3], vcols[3][3];
    sym3_eigen_scaled(ftf, evals, vcols);
    double b[3][3];
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) b[j][i] = dot3(fm[i], vcols[j]);
    double r00 = std::sqrt(dot3(b[0], b[0]));
    double ucols[3][3];
    for (int k = 0; k < 3; ++k) ucols[0][k] = b[0][k] * (1.0 / r00);
    orthonormal_against(ucols[0], b[1], r00, ucols[1]);
    cross3(ucols[0], ucols[1], ucols[2]);
    double r12 = dot3(ucols[1], b[2]);
    double sigma[3] = {r00, dot3(ucols[1], b[1]), dot3(ucols[2], b[2])};
    if (std::fabs(r12) > 4.0 * EPS * r00)
        trailing_2x2(sigma[1], r12, sigma[2], sigma, ucols, vcols);
    fix_order(sigma, ucols, vcols);
    for (int k = 0; k < 3; ++k) out.sigma[k] = sigma[k] / s1 / s2;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            out.u[i][j] = ucols[j][i];
            out.v[i][j] = vcols[j][i];
        }
    return out;
}

/// Signed SVD for D = 2 or 3.
template <int D>
ECC_HOST_DEVICE inline Svd<D> signed_svd(const double (&f)[D][D]) {
    static_assert(D == 2 || D == 3, "signed_svd supports D = 2 or 3");
    if constexpr (D == 2) {
        return signed_svd2(f);
    } else {
        return signed_svd3(f);
    }
}

// ------------------------------------------------ filtered scaling block

/// The pair (i, j) of slot k (spectral.rs `pair_indices`).
template <int D>
ECC_HOST_DEVICE inline void pair_indices(int k, int& i, int& j) {
    if (D == 2) {
        i = 0;
        j = 1;
    } else {
        i = (k + 1) % 3;
        j = (k + 2) % 3;
    }
}

/// The filtered stretch-space data needed for assembly (assemble.rs `Filtered`).
template <int D>
struct Filtered {
    double scale[D][D];
    bool diagonal;
    double twist[3];
    double flip[3];
};

namespace detail {

/// Number of eigenvalues of A below `floor` from the LDLᵀ pivots of A − floor·I;
/// −1 when a pivot vanishes or is not finite (assemble.rs `below_floor`).
template <int D>
ECC_HOST_DEVICE inline int below_floor(const double a[D][D], double floor) {
    double d0 = a[0][0] - floor;
    if (d0 == 0.0 || !std::isfinite(d0)) return -1;
    double l10 = a[1][0] / d0;
    double d1 = a[1][1] - floor - a[1][0] * l10;
    if (d1 == 0.0 || !std::isfinite(d1)) return -1;
    int neg = (d0 < 0.0 ? 1 : 0) + (d1 < 0.0 ? 1 : 0);
    if constexpr (D == 3) {
        double l20 = a[2][0] / d0;
        double l21 = (a[2][1] - a[2][0] * l10) / d1;
        double d2 = a[2][2] - floor - a[2][0] * l20 - l21 * l21 * d1;
        if (!std::isfinite(d2)) return -1;
        neg += d2 < 0.0 ? 1 : 0;
    }
    return neg;
}

/// Â = filter(A) for a finite symmetric 3×3 with at most one eigenpair
/// (assemble.rs `filter_block3`); false when the pivots break down.
ECC_HOST_DEVICE inline bool filter_block3(const double a[3][3], Filter filter, double out[3][3]) {
    double floor = filter.floor();
    int k = below_floor<3>(a, floor);
    if (k < 0) return false;
    auto id = [](int i, int j) { return i == j ? 1.0 : 0.0; };
    if (k == 0) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) out[i][j] = a[i][j];
        return true;
    }
    if (k == 3) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                out[i][j] = filter.kind == FilterKind::Abs ? -a[i][j] : floor * id(i, j);
        return true;
    }
    double an[3][3], scale;
    if (!normalised(a, an, scale)) return false;
    Isolated iso;
    bool has = isolated_scaled(an, iso);
    if (has && ((k == 1) != iso.is_max)) {
        double l = iso.value * scale;
        const double* z = iso.vector;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                if (k == 1) {
                    out[i][j] = a[i][j] + (filter.apply(l) - l) * z[i] * z[j];
                } else if (filter.kind == FilterKind::Abs) {
                    out[i][j] = -a[i][j] + 2.0 * l * z[i] * z[j];
                } else {
                    out[i][j] = l * z[i] * z[j] + floor * (id(i, j) - z[i] * z[j]);
                }
            }
        return true;
    }
    double vals[3], vecs[3][3];
    complete_scaled(an, has ? &iso : nullptr, vals, vecs);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out[i][j] = 0.0;
    for (int m = 0; m < 3; ++m) {
        double l = filter.apply(vals[m] * scale);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) out[i][j] += l * vecs[m][i] * vecs[m][j];
    }
    return true;
}

/// Â for a finite symmetric block the filter changes (assemble.rs `filter_block`).
template <int D>
ECC_HOST_DEVICE inline void filter_block(const double a[D][D], Filter filter, double out[D][D]) {
    if constexpr (D == 3) {
        if (filter_block3(a, filter, out)) return;
    }
    double vals[3] = {0.0, 0.0, 0.0};
    double vecs[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    if constexpr (D == 2) {
        double v2[2], z2[2][2];
        sym2_eigen(a[0][0], 0.5 * (a[0][1] + a[1][0]), a[1][1], v2, z2);
        vals[0] = v2[0]; vals[1] = v2[1];
        vecs[0][0] = z2[0][0]; vecs[0][1] = z2[0][1];
        vecs[1][0] = z2[1][0]; vecs[1][1] = z2[1][1];
    } else {
        double m[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) m[i][j] = 0.5 * (a[i][j] + a[j][i]);
        sym3_eigen(m, vals, vecs);
    }
    for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) out[i][j] = 0.0;
    for (int m = 0; m < D; ++m) {
        double l = filter.apply(vals[m]);
        for (int i = 0; i < D; ++i)
            for (int j = 0; j < D; ++j) out[i][j] += l * vecs[m][i] * vecs[m][j];
    }
}

}  // namespace detail

/// Filter the spectral data of one point (assemble.rs `Filtered::new`).
template <int D>
ECC_HOST_DEVICE inline Filtered<D> filtered(const Spectral<D>& s, Filter filter) {
    constexpr int pairs = D * (D - 1) / 2;
    Filtered<D> f{};
    for (int k = 0; k < pairs; ++k) {
        f.twist[k] = filter.apply(s.twist[k]);
        f.flip[k] = filter.apply(s.flip[k]);
    }
    f.diagonal = true;
    if (s.diagonal) {
        for (int i = 0; i < D; ++i) f.scale[i][i] = filter.apply(s.scale[i][i]);
        return f;
    }
    bool finite = true;
    for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) finite = finite && std::isfinite(s.scale[i][j]);
    if (!finite) {
        // Documented fallback: keep the diagonal only.
        for (int i = 0; i < D; ++i) f.scale[i][i] = filter.apply(s.scale[i][i]);
        return f;
    }
    double sym[D][D];
    for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) sym[i][j] = 0.5 * (s.scale[i][j] + s.scale[j][i]);
    if (filter.is_raw() || detail::below_floor<D>(sym, filter.floor()) == 0) {
        for (int i = 0; i < D; ++i)
            for (int j = 0; j < D; ++j) f.scale[i][j] = sym[i][j];
    } else {
        detail::filter_block<D>(sym, filter, f.scale);
    }
    f.diagonal = false;
    return f;
}

// ------------------------------------------------------ modal assembly

namespace detail {

/// u ⊗ w node-major: p[n·D + r] = u[r]·w[n] (modes.rs `outer`).
template <int D, int K>
ECC_HOST_DEVICE inline void outer(const double u[D], const double w[K], double p[D * K]) {
    for (int n = 0; n < K; ++n)
        for (int r = 0; r < D; ++r) p[n * D + r] = u[r] * w[n];
}

}  // namespace detail

/// Σ_i weight·grad_i · u_i ⊗ w_i (modes.rs `gradient_vec`); u[i], w[i] are the
/// i-th left vector and its (x-space) right vector.
template <int D, int K>
ECC_HOST_DEVICE inline void gradient_vec(const double u[D][D], const double w[D][K],
                                         const double grad[D], double weight, double out[D * K]) {
    constexpr int N = D * K;
    for (int x = 0; x < N; ++x) out[x] = 0.0;
    double p[N];
    for (int i = 0; i < D; ++i) {
        double c = weight * grad[i];
        detail::outer<D, K>(u[i], w[i], p);
        for (int x = 0; x < N; ++x) out[x] += c * p[x];
    }
}

/// H = weight · Σ over the finite modes (assemble.rs `modal_parts`): the scaling
/// block Σ_ij Â_ij p_ii p_jjᵀ and per pair λ_t/2 (p_ji − p_ij)(…)ᵀ + λ_l/2 (p_ji + p_ij)(…)ᵀ,
/// with p_ab = u_a ⊗ w_b, minus a repeated pair value c handled as
/// c·(I_d ⊗ G), G_nm = Σ_b w_b,n w_b,m. Upper triangle, then mirrored.
/// Modes with λ = ±∞ (a pole; raw Hessian only) are kept apart: returns
/// whether there were any, with P = Σ sign(λ) g gᵀ over them in `p`.
template <int D, int M>
ECC_HOST_DEVICE inline bool modal_parts(const double u[D][D], const double w[D][M],
                                        const Filtered<D>& f, double weight,
                                        double h[D * M][D * M], double p[D * M][D * M]) {
    constexpr int R = D * M;
    constexpr int pairs = D * (D - 1) / 2;
    double vals[9];
    int nc = 0;
    for (int k = 0; k < pairs; ++k) {
        vals[nc] = f.twist[k];
        vals[nc + 1] = f.flip[k];
        nc += 2;
    }
    if (f.diagonal)
        for (int i = 0; i < D; ++i) vals[nc++] = f.scale[i][i];
    double shift = 0.0;
    int best = 1;
    const double cands[3] = {f.flip[0], f.twist[0], f.scale[0][0]};
    for (double c : cands) {
        if (c != 0.0 && std::isfinite(c)) {
            int count = 0;
            for (int x = 0; x < nc; ++x) count += vals[x] == c ? 1 : 0;
            if (count > best) {
                best = count;
                shift = c;
            }
        }
    }
    for (int i = 0; i < R; ++i)
        for (int j = 0; j < R; ++j) h[i][j] = 0.0;
    double vecs[12][R];
    int upd_l[9], upd_r[9];
    double upd_c[9];
    int inf_l[9];
    double inf_c[9];
    int nv = 0, nu = 0, ni = 0;
    // A rank-one update c·v vᵀ (v = vecs[l]): finite, or ±∞ (kept apart).
    auto push = [&](int l, double c) {
        if (std::isinf(c)) {
            inf_l[ni] = l; inf_c[ni] = c; ++ni;
        } else {
            upd_l[nu] = l; upd_r[nu] = l; upd_c[nu] = c; ++nu;
        }
    };
    if (shift != 0.0) {
        double c = shift * weight;
        for (int n = 0; n < M; ++n)
            for (int q = n; q < M; ++q) {
                double g = 0.0;
                for (int b = 0; b < D; ++b) g += w[b][n] * w[b][q];
                for (int r = 0; r < D; ++r) h[n * D + r][q * D + r] = c * g;
            }
    }
    double sc[D][D];
    for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) sc[i][j] = f.scale[i][j];
    for (int i = 0; i < D; ++i) sc[i][i] -= shift;
    double pii[D][R];
    for (int i = 0; i < D; ++i) detail::outer<D, M>(u[i], w[i], pii[i]);
    if (f.diagonal) {
        for (int i = 0; i < D; ++i) {
            if (sc[i][i] != 0.0) {
                for (int x = 0; x < R; ++x) vecs[nv][x] = pii[i][x];
                push(nv, sc[i][i] * weight);
                ++nv;
            }
        }
    } else {
        for (int i = 0; i < D; ++i) {
            double y[R];
            for (int x = 0; x < R; ++x) y[x] = 0.0;
            for (int j = 0; j < D; ++j) {
                double c = sc[i][j] * weight;
                for (int x = 0; x < R; ++x) y[x] += c * pii[j][x];
            }
            for (int x = 0; x < R; ++x) {
                vecs[nv][x] = pii[i][x];
                vecs[nv + 1][x] = y[x];
            }
            upd_l[nu] = nv; upd_r[nu] = nv + 1; upd_c[nu] = 1.0;
            nv += 2;
            ++nu;
        }
    }
    for (int k = 0; k < pairs; ++k) {
        int i, j;
        pair_indices<D>(k, i, j);
        double lt = f.twist[k] - shift;
        double ll = f.flip[k] - shift;
        if (lt == 0.0 && ll == 0.0) continue;
        double pji[R], pij[R];
        detail::outer<D, M>(u[j], w[i], pji);
        detail::outer<D, M>(u[i], w[j], pij);
        if (lt != 0.0) {
            for (int x = 0; x < R; ++x) vecs[nv][x] = pji[x] - pij[x];
            push(nv, 0.5 * lt * weight);
            ++nv;
        }
        if (ll != 0.0) {
            for (int x = 0; x < R; ++x) vecs[nv][x] = pji[x] + pij[x];
            push(nv, 0.5 * ll * weight);
            ++nv;
        }
    }
    for (int i = 0; i < R; ++i) {
        double row[R];
        for (int j = 0; j < R; ++j) row[j] = h[i][j];
        for (int m = 0; m < nu; ++m) {
            double ci = upd_c[m] * vecs[upd_l[m]][i];
            const double* rv = vecs[upd_r[m]];
            for (int j = 0; j < R; ++j) row[j] += ci * rv[j];
        }
        for (int j = 0; j < R; ++j) h[i][j] = row[j];
    }
    for (int i = 0; i < R; ++i)
        for (int j = i + 1; j < R; ++j) h[j][i] = h[i][j];
    if (ni == 0) return false;
    for (int i = 0; i < R; ++i)
        for (int j = 0; j < R; ++j) p[i][j] = 0.0;
    for (int m = 0; m < ni; ++m) {
        const double* v = vecs[inf_l[m]];
        double sg = inf_c[m] > 0.0 ? 1.0 : -1.0;
        for (int i = 0; i < R; ++i)
            for (int j = 0; j < R; ++j) p[i][j] += sg * v[i] * v[j];
    }
    return true;
}

/// H_xy = sign(P_xy)·∞ where P_xy ≠ 0, a NaN entry staying NaN (assemble.rs
/// `saturate`).
template <int N>
ECC_HOST_DEVICE inline void saturate(double h[N][N], const double p[N][N]) {
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j)
            if (p[i][j] != 0.0 && !std::isnan(h[i][j]))
                h[i][j] = p[i][j] > 0.0 ? infinity() : -infinity();
}

/// H = weight · Σ over the modes (assemble.rs `modal_sum`): [`modal_parts`],
/// then ±∞ wherever an infinite mode reaches (never ∞·0 = NaN).
template <int D, int M>
ECC_HOST_DEVICE inline void modal_sum(const double u[D][D], const double w[D][M],
                                      const Filtered<D>& f, double weight,
                                      double h[D * M][D * M]) {
    double p[D * M][D * M];
    if (modal_parts<D, M>(u, w, f, weight, h, p)) saturate<D * M>(h, p);
}

/// Expand the block of nodes 1…K−1 to all K nodes with the zero node-sums
/// (assemble.rs `expand_nodes`).
template <int D, int K>
ECC_HOST_DEVICE inline void expand_nodes(const double h[D * (K - 1)][D * (K - 1)],
                                         double out[D * K][D * K]) {
    constexpr int R = D * (K - 1);
    constexpr int N = D * K;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) out[i][j] = 0.0;
    for (int i = 0; i < R; ++i)
        for (int j = 0; j < R; ++j) out[D + i][D + j] = h[i][j];
    for (int r = 0; r < D; ++r)
        for (int j = D; j < N; ++j) {
            double s = 0.0;
            for (int n = 1; n < K; ++n) s += out[n * D + r][j];
            out[r][j] = -s;
            out[j][r] = -s;
        }
    for (int r = 0; r < D; ++r)
        for (int s2 = r; s2 < D; ++s2) {
            double s = 0.0;
            for (int m = 1; m < K; ++m) s += out[r][m * D + s2];
            out[r][s2] = -s;
            out[s2][r] = -s;
        }
}

// ------------------------------------------------------- entry points

/// Energy, vec(∂Ψ/∂F) (column-major) and the (filtered) d²×d² Hessian at F.
template <int D>
struct PointEval {
    double psi;
    double grad[D * D];
    double hess[D * D][D * D];
};

/// Energy, gradient and Hessian of one element, times its rest measure
/// (node-major, N = D·(D+1)).
template <int N>
struct ElementEval {
    double psi;
    double grad[N];
    double hess[N][N];
};

namespace detail {
template <int D>
ECC_HOST_DEVICE inline void columns(const double m[D][D], double out[D][D]) {
    for (int j = 0; j < D; ++j)
        for (int i = 0; i < D; ++i) out[j][i] = m[i][j];
}
}  // namespace detail

/// Ψ(F) of `energy` (any type with `double psi(const double (&)[D]) const`).
template <int D, class E>
ECC_HOST_DEVICE inline double psi_f(const E& energy, const double (&F)[D][D]) {
    for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j)
            if (!std::isfinite(F[i][j])) return nan();
    Svd<D> svd = signed_svd<D>(F);
    return energy.psi(svd.sigma);
}

/// Ψ, vec(∂Ψ/∂F) and ∂²Ψ/∂f² at F (point.rs), filtered by `filter`
/// (Filter::none() = raw). Outside the domain (Ψ = +∞) the gradient is 0 and
/// the Hessian filter(0); a non-finite F gives Ψ = NaN, a zero gradient, and a zero filtered
/// (NaN raw) Hessian.
template <int D, class E>
ECC_HOST_DEVICE inline PointEval<D> eval_f(const E& energy, const double (&F)[D][D], Filter filter,
                                           bool want_hessian = true) {
    constexpr int N = D * D;
    PointEval<D> out{};
    Svd<D> svd = signed_svd<D>(F);
    if (!svd.is_finite()) {
        out.psi = nan();
        double fill = filter.is_raw() && want_hessian ? nan() : 0.0;
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) out.hess[i][j] = fill;
        return out;
    }
    // Outside the domain the spectral data are Ψ = +∞ and zeros: the gradient
    // is 0 and the Hessian filter(0) (0, or ε·I for ClampEps), as in Rust.
    Spectral<D> s = energy.spectral(svd.sigma);
    out.psi = s.psi;
    double u[D][D], v[D][D];
    detail::columns<D>(svd.u, u);
    detail::columns<D>(svd.v, v);
    gradient_vec<D, D>(u, v, s.grad, 1.0, out.grad);
    if (want_hessian) modal_sum<D, D>(u, v, filtered<D>(s, filter), 1.0, out.hess);
    return out;
}

/// The element kernel (element/eval.rs `element_eval`): F and Dm⁻¹, the rest
/// measure; x-space vectors w_b = β v_b with β_n = row n−1 of Dm⁻¹ (n ≥ 1),
/// β_0 = −Σ β_n, so that no d²×d(D+1) matrix is formed.
template <int D, class E>
ECC_HOST_DEVICE inline ElementEval<D*(D + 1)> eval_element_f(const E& energy,
                                                             const double (&F)[D][D],
                                                             const double (&dm_inv)[D][D],
                                                             double measure, Filter filter,
                                                             bool want_hessian = true) {
    constexpr int K = D + 1;
    ElementEval<D * K> out{};
    Svd<D> svd = signed_svd<D>(F);
    if (!svd.is_finite()) {
        out.psi = nan();
        return out;
    }
    Spectral<D> s = energy.spectral(svd.sigma);
    if (!std::isfinite(s.psi)) {
        out.psi = measure * s.psi;
        return out;
    }
    double u[D][D];
    detail::columns<D>(svd.u, u);
    double w[D][K];
    for (int b = 0; b < D; ++b) {
        double sum = 0.0;
        for (int n = 1; n < K; ++n) {
            double acc = 0.0;
            for (int c = 0; c < D; ++c) acc += dm_inv[n - 1][c] * svd.v[c][b];
            w[b][n] = acc;
            sum += acc;
        }
        w[b][0] = -sum;
    }
    gradient_vec<D, K>(u, w, s.grad, measure, out.grad);
    if (want_hessian) {
        double wr[D][D];
        for (int b = 0; b < D; ++b)
            for (int n = 0; n < D; ++n) wr[b][n] = w[b][n + 1];
        // Infinite modes' P expanded to node 0 like H (assemble.rs `modal_sum_nodes`).
        double hr[D * D][D * D], pr[D * D][D * D];
        bool inf = modal_parts<D, D>(u, wr, filtered<D>(s, filter), measure, hr, pr);
        expand_nodes<D, K>(hr, out.hess);
        if (inf) {
            double pn[D * K][D * K];
            expand_nodes<D, K>(pr, pn);
            saturate<D * K>(out.hess, pn);
        }
    }
    out.psi = measure * s.psi;
    return out;
}

/// F = Ds Dm⁻¹ of a triangle (x: 3 nodes × 2 coordinates).
ECC_HOST_DEVICE inline void tri_f(const double (&x)[3][2], const double (&dm_inv)[2][2],
                                  double (&F)[2][2]) {
    const double ds[2][2] = {{x[1][0] - x[0][0], x[2][0] - x[0][0]},
                             {x[1][1] - x[0][1], x[2][1] - x[0][1]}};
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) F[i][j] = ds[i][0] * dm_inv[0][j] + ds[i][1] * dm_inv[1][j];
}

/// F = Ds Dm⁻¹ of a tetrahedron (x: 4 nodes × 3 coordinates).
ECC_HOST_DEVICE inline void tet_f(const double (&x)[4][3], const double (&dm_inv)[3][3],
                                  double (&F)[3][3]) {
    double ds[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) ds[i][j] = x[j + 1][i] - x[0][i];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            F[i][j] = 0.0;
            for (int k = 0; k < 3; ++k) F[i][j] += ds[i][k] * dm_inv[k][j];
        }
}

/// Energy, gradient and Hessian (6×6) of a linear triangle, × its rest area.
template <class E>
ECC_HOST_DEVICE inline ElementEval<6> eval_tri(const E& energy, const double (&x)[3][2],
                                               const double (&dm_inv)[2][2], double area,
                                               Filter filter, bool want_hessian = true) {
    double F[2][2];
    tri_f(x, dm_inv, F);
    return eval_element_f<2>(energy, F, dm_inv, area, filter, want_hessian);
}

/// Energy, gradient and Hessian (12×12) of a linear tetrahedron, × its rest volume.
template <class E>
ECC_HOST_DEVICE inline ElementEval<12> eval_tet(const E& energy, const double (&x)[4][3],
                                                const double (&dm_inv)[3][3], double volume,
                                                Filter filter, bool want_hessian = true) {
    double F[3][3];
    tet_f(x, dm_inv, F);
    return eval_element_f<3>(energy, F, dm_inv, volume, filter, want_hessian);
}

// ------------------------------------------------------------ fibres
//
// Fibre (anisotropic) energies ψ(I4, I5) of a unit rest-space direction a
// (runtime/core/src/fibre*: the same formulas, the same order):
//
//   I4 = aᵀ S a = Σ σ_i b_i², b = Vᵀ a (signed polar F = R S, S = V Σ Vᵀ)  (F1)
//   I5 = ‖F a‖²                                                          (F2)
//   ∂ψ/∂F = ψ4 g4 + ψ5 g5                                                (P1)
//   ∂²ψ/∂f² = ψ5 H5 + ψ4 H4 + [g4 g5] [[ψ44, ψ45], [ψ45, ψ55]] [g4 g5]ᵀ   (P2)
//
// with g5 = vec(2 F a aᵀ), H5 = 2 (a aᵀ ⊗ I) (eq. F3; Kim, de Goes & Iben
// 2019 §4.1 eqs. 6–7), g4 from eq. F4 and H4 from the bilinear form F5
// (fibre/frame.rs). A ψ without an I4 derivative at the point (every ψ(I5),
// and anisotropic ARAP, whose sign(I4) is locally constant) has the closed
// eigensystem (fibre/point.rs)
//
//   λ_along = 2ψ5 + 4ψ55 I5 on vec(n aᵀ), n = F a/‖F a‖,                 (P3)
//   λ_across = 2ψ5 on vec(q aᵀ), q ⊥ n,                                  (P4)
//   0 on vec(q cᵀ), c ⊥ a,                                               (P5)
//
// filtered eigenvalue by eigenvalue with no eigensolve. A ψ with I4 terms
// is filtered by a Jacobi eigensolve of the d²×d² Hessian P2 (the Rust F5
// path, `FibrePath::Numeric`; the Rust runtime's smaller reduced block of
// fibre/reduced.rs is a speed-up that gives the same matrix to rounding).
// An energy E provides `template <int D> FibreDerivs fibre(double i4,
// double i5) const` and `static constexpr FibreUse fibre_uses(int d)`.

/// ψ and its partials with respect to (I4, I5) at one point (fibre.rs
/// `FibreDerivs`); ψ = +∞ outside the domain, the partials then 0.
struct FibreDerivs {
    double psi;
    double d4;
    double d5;
    double d44;
    double d45;
    double d55;

    /// Outside the domain: ψ = +∞, every partial 0.
    ECC_HOST_DEVICE static FibreDerivs infinite() {
        FibreDerivs d{};
        d.psi = infinity();
        return d;
    }
};

/// Which fibre invariants ψ reads (fibre.rs `FibreUse`, decided by the CAS):
/// I4 is computed (one signed SVD) only for I4 and Both.
enum class FibreUse { None, I4, I5, Both };

/// Which eigensystem produced a fibre Hessian (point.rs `FibrePath`).
enum class FibrePath {
    /// ψ not finite or F not finite: zero derivatives.
    Degenerate,
    /// Closed form P3–P5 (no I4 derivative at this point).
    ClosedI5,
    /// P2 with the analytic H4 (eq. F5), filtered by a d²×d² eigensolve.
    Numeric,
};

/// ψ, I4, I5, vec(∂ψ/∂F) (column-major) and the filtered d²×d² ∂²ψ/∂f².
template <int D>
struct FibreEval {
    double psi;
    /// I4 (NaN when ψ does not read it: no SVD was taken).
    double i4;
    double i5;
    double grad[D * D];
    double hess[D * D][D * D];
    FibrePath path;
};

namespace detail {

/// x·c with 0·(±∞) = 0 (frame.rs `mul0`): a zero factor is exact.
ECC_HOST_DEVICE inline double mul0(double c, double x) { return x == 0.0 ? 0.0 : c * x; }

/// F a and I5 = ‖F a‖² (frame.rs `fa_i5`).
template <int D>
ECC_HOST_DEVICE inline double fa_i5(const double (&F)[D][D], const double (&a)[D], double fa[D]) {
    double i5 = 0.0;
    for (int r = 0; r < D; ++r) {
        double s = 0.0;
        for (int c = 0; c < D; ++c) s += F[r][c] * a[c];
        fa[r] = s;
    }
    for (int r = 0; r < D; ++r) i5 += fa[r] * fa[r];
    return i5;
}

/// Singular frame, b = Vᵀ a and I4 of one F (frame.rs `Frame`).
template <int D>
struct FibreFrame {
    Svd<D> svd;
    double b[D];
    double i4;

    /// No frame (ψ does not read I4: no SVD is taken); I4 = NaN.
    ECC_HOST_DEVICE FibreFrame() : svd{}, b{}, i4(nan()) {}

    ECC_HOST_DEVICE FibreFrame(const double (&F)[D][D], const double (&a)[D])
        : svd(signed_svd<D>(F)), b{}, i4(0.0) {
        for (int i = 0; i < D; ++i) {
            double s = 0.0;
            for (int c = 0; c < D; ++c) s += svd.v[c][i] * a[c];
            b[i] = s;
        }
        for (int i = 0; i < D; ++i) i4 += svd.sigma[i] * b[i] * b[i];
    }

    /// ∂I4/∂M in the singular frame (eq. F4).
    ECC_HOST_DEVICE void grad4_m(double g[D][D]) const {
        const double* s = svd.sigma;
        for (int r = 0; r < D; ++r)
            for (int c = 0; c < D; ++c) {
                if (r == c) {
                    g[r][c] = b[r] * b[r];
                } else {
                    double num = 2.0 * b[r] * b[c] * s[r];
                    g[r][c] = num == 0.0 ? 0.0 : num / (s[r] + s[c]);
                }
            }
    }

    /// vec(U X Vᵀ) (column-major) of a singular-frame matrix X.
    ECC_HOST_DEVICE void to_f(const double x[D][D], double out[D * D]) const {
        for (int r = 0; r < D; ++r)
            for (int c = 0; c < D; ++c) {
                double s = 0.0;
                for (int i = 0; i < D; ++i)
                    for (int j = 0; j < D; ++j) s += svd.u[r][i] * x[i][j] * svd.v[c][j];
                out[c * D + r] = s;
            }
    }

    /// G(M) of eq. F5: the first variation of S in the singular frame.
    ECC_HOST_DEVICE void g(const double m[D][D], double out[D][D]) const {
        const double* s = svd.sigma;
        for (int p = 0; p < D; ++p)
            for (int q = 0; q < D; ++q) {
                if (p == q) {
                    out[p][q] = m[p][p];
                } else {
                    double num = s[p] * m[p][q] + s[q] * m[q][p];
                    out[p][q] = num == 0.0 ? 0.0 : num / (s[p] + s[q]);
                }
            }
    }

    /// B(M, N) of eq. F5 (off-diagonal terms, then the cancellation-free D_p).
    ECC_HOST_DEVICE double bilinear(const double m[D][D], const double n[D][D]) const {
        const double* s = svd.sigma;
        double gm[D][D], gn[D][D];
        g(m, gm);
        g(n, gn);
        double acc = 0.0;
        for (int p = 0; p < D; ++p)
            for (int q = 0; q < D; ++q) {
                if (p == q || b[p] * b[q] == 0.0) continue;
                double x = 0.0;
                for (int k = 0; k < D; ++k)
                    x += m[k][p] * n[k][q] + n[k][p] * m[k][q] - gm[p][k] * gn[k][q] -
                         gn[p][k] * gm[k][q];
                acc += b[p] * b[q] * mul0(1.0 / (s[p] + s[q]), x);
            }
        for (int p = 0; p < D; ++p) {
            if (b[p] == 0.0) continue;
            double dp = 0.0;
            for (int k = 0; k < D; ++k) {
                if (k == p) continue;
                double m1 = m[p][k], m2 = m[k][p], n1 = n[p][k], n2 = n[k][p];
                double sum = s[p] + s[k];
                double t = 2.0 * m2 * n2 - m2 * n1 - n2 * m1 - mul0(s[p] / sum, (m2 - m1) * (n2 - n1));
                dp += mul0(1.0 / sum, t);
            }
            acc += b[p] * b[p] * dp;
        }
        return acc;
    }

    /// ∂²I4/∂f² (eq. F5 rotated to F-space by V ⊗ U).
    ECC_HOST_DEVICE void hess4(double h[D * D][D * D]) const {
        constexpr int N = D * D;
        double hm[N][N];
        for (int i = 0; i < N; ++i)
            for (int j = i; j < N; ++j) {
                double ei[D][D] = {}, ej[D][D] = {};
                ei[i % D][i / D] = 1.0;
                ej[j % D][j / D] = 1.0;
                hm[i][j] = hm[j][i] = bilinear(ei, ej);
            }
        double k[N][N];
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) k[i][j] = svd.v[i / D][j / D] * svd.u[i % D][j % D];
        double t[N][N];
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) {
                double s = 0.0;
                for (int x = 0; x < N; ++x) s += k[i][x] * hm[x][j];
                t[i][j] = s;
            }
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) {
                double s = 0.0;
                for (int x = 0; x < N; ++x) s += t[i][x] * k[j][x];
                h[i][j] = s;
            }
    }
};

/// Eigenvalues and eigenvectors (columns of `q`) of a finite symmetric N×N
/// by cyclic Jacobi rotations (Golub & Van Loan §8.5, Rutishauser's stable
/// rotation), to full working accuracy.
template <int N>
ECC_HOST_DEVICE inline void jacobi_eigen(double a[N][N], double vals[N], double q[N][N]) {
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) q[i][j] = i == j ? 1.0 : 0.0;
    for (int sweep = 0; sweep < 100; ++sweep) {
        double off = 0.0, diag = 0.0;
        for (int i = 0; i < N; ++i) {
            diag += a[i][i] * a[i][i];
            for (int j = i + 1; j < N; ++j) off += a[i][j] * a[i][j];
        }
        if (off == 0.0 || off <= EPS * EPS * EPS * EPS * (diag + 2.0 * off)) break;
        for (int p = 0; p < N; ++p)
            for (int r = p + 1; r < N; ++r) {
                double apr = a[p][r];
                if (apr == 0.0) continue;
                // t = tan of the rotation angle, the smaller root of t² + 2θt − 1 = 0.
                double theta = (a[r][r] - a[p][p]) / (2.0 * apr);
                double t = std::fabs(theta) > 1e150
                               ? 0.5 / theta
                               : std::copysign(1.0, theta) /
                                     (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
                double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < N; ++k) {
                    double akp = a[k][p], akr = a[k][r];
                    a[k][p] = c * akp - s * akr;
                    a[k][r] = s * akp + c * akr;
                }
                for (int k = 0; k < N; ++k) {
                    double apk = a[p][k], ark = a[r][k];
                    a[p][k] = c * apk - s * ark;
                    a[r][k] = s * apk + c * ark;
                }
                a[p][r] = a[r][p] = 0.0;
                for (int k = 0; k < N; ++k) {
                    double qkp = q[k][p], qkr = q[k][r];
                    q[k][p] = c * qkp - s * qkr;
                    q[k][r] = s * qkp + c * qkr;
                }
            }
    }
    for (int i = 0; i < N; ++i) vals[i] = a[i][i];
}

}  // namespace detail

/// Filter a symmetric N×N matrix eigenvalue by eigenvalue (reference/mod.rs
/// `project_psd_numeric`): symmetrised; returned as is for Filter::none();
/// a non-finite matrix projects to 0.
template <int N>
ECC_HOST_DEVICE inline void project_psd(const double h[N][N], Filter filter, double out[N][N]) {
    double sym[N][N];
    bool finite = true;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            sym[i][j] = 0.5 * (h[i][j] + h[j][i]);
            finite = finite && std::isfinite(sym[i][j]);
        }
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) out[i][j] = filter.is_raw() ? sym[i][j] : 0.0;
    if (filter.is_raw() || !finite) return;
    double vals[N], q[N][N];
    detail::jacobi_eigen<N>(sym, vals, q);
    for (int k = 0; k < N; ++k) vals[k] = filter.apply(vals[k]);
    for (int i = 0; i < N; ++i)
        for (int j = i; j < N; ++j) {
            double acc = 0.0;
            for (int k = 0; k < N; ++k) acc += q[i][k] * vals[k] * q[j][k];
            out[i][j] = out[j][i] = acc;
        }
}

/// I4 = aᵀ S a with the signed SVD's S = V Σ Vᵀ (eq. F1); `a` a unit vector.
template <int D>
ECC_HOST_DEVICE inline double fibre_invariant4(const double (&F)[D][D], const double (&a)[D]) {
    return detail::FibreFrame<D>(F, a).i4;
}

/// I5 = ‖F a‖² (eq. F2).
template <int D>
ECC_HOST_DEVICE inline double fibre_invariant5(const double (&F)[D][D], const double (&a)[D]) {
    double fa[D];
    return detail::fa_i5<D>(F, a, fa);
}

/// a/‖a‖ into `out`; false (out untouched) for a zero or non-finite vector
/// (fibre/dim.rs `unit_fibre`).
template <int D>
ECC_HOST_DEVICE inline bool unit_fibre(const double (&dir)[D], double (&out)[D]) {
    double n2 = 0.0;
    for (int i = 0; i < D; ++i) {
        if (!std::isfinite(dir[i])) return false;
        n2 += dir[i] * dir[i];
    }
    double n = std::sqrt(n2);
    if (!(std::isfinite(n) && n > 0.0)) return false;
    for (int i = 0; i < D; ++i) out[i] = dir[i] / n;
    return true;
}

namespace detail {

/// Unit n = F a/‖F a‖ (e₀ when F a = 0), scaled first (point.rs `unit`).
template <int D>
ECC_HOST_DEVICE inline void unit_fa(const double fa[D], double n[D]) {
    double m = 0.0;
    for (int i = 0; i < D; ++i) m = ecc::fmax(m, std::fabs(fa[i]));
    if (m == 0.0) {
        for (int i = 0; i < D; ++i) n[i] = i == 0 ? 1.0 : 0.0;
        return;
    }
    double y[D], s = 0.0;
    for (int i = 0; i < D; ++i) {
        y[i] = fa[i] / m;
        s += y[i] * y[i];
    }
    s = std::sqrt(s);
    for (int i = 0; i < D; ++i) n[i] = y[i] / s;
}

/// The closed-form Hessian of eqs. P3–P5 from the filtered eigenvalues
/// f = [along, across, null]: f0 (I − P) + f_across (P − e eᵀ) + f_along e eᵀ,
/// P = a aᵀ ⊗ I, e = a ⊗ n (point.rs `closed_hessian`).
template <int D>
ECC_HOST_DEVICE inline void closed_hessian(const double f[3], const double (&a)[D], const double n[D],
                                           double h[D * D][D * D]) {
    constexpr int N = D * D;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            int ci = i / D, ri = i % D, cj = j / D, rj = j % D;
            double p = ri == rj ? a[ci] * a[cj] : 0.0;
            double e = a[ci] * n[ri] * a[cj] * n[rj];
            double id = i == j ? 1.0 : 0.0;
            h[i][j] = mul0(f[2], id - p) + mul0(f[1], p - e) + mul0(f[0], e);
        }
}

/// The raw Hessian P2 (point.rs `raw_hessian`); NaN entries become +∞.
template <int D>
ECC_HOST_DEVICE inline void fibre_raw_hessian(const FibreFrame<D>& fr, const double (&a)[D],
                                              const FibreDerivs& d, const double g4[D * D],
                                              const double g5[D * D], double h[D * D][D * D]) {
    constexpr int N = D * D;
    double h4[N][N] = {};
    if (d.d4 != 0.0) fr.hess4(h4);
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            double h5 = i % D == j % D ? 2.0 * a[i / D] * a[j / D] : 0.0;
            double v = mul0(d.d5, h5) + mul0(d.d4, h4[i][j]) + mul0(d.d44, g4[i] * g4[j]) +
                       mul0(d.d45, g4[i] * g5[j] + g5[i] * g4[j]) + mul0(d.d55, g5[i] * g5[j]);
            h[i][j] = std::isnan(v) ? infinity() : v;
        }
}

/// The fibre point kernel (point.rs `point_kernel`): ψ, I4, I5, gradient and,
/// if asked, the filtered Hessian, with the closed filtered eigenvalues and n
/// in `closed`/`n` when the path is ClosedI5 (then `hess` is not filled).
template <int D, class E>
ECC_HOST_DEVICE inline FibreEval<D> fibre_kernel(const E& energy, const double (&F)[D][D],
                                                 const double (&a)[D], Filter filter,
                                                 bool want_hessian, double closed[3], double n[D]) {
    constexpr int N = D * D;
    FibreEval<D> out{};
    out.path = FibrePath::Degenerate;
    out.i4 = nan();
    for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j)
            if (!std::isfinite(F[i][j])) {
                out.psi = nan();
                out.i5 = nan();
                return out;
            }
    constexpr FibreUse uses = E::fibre_uses(D);
    constexpr bool reads_i4 = uses == FibreUse::I4 || uses == FibreUse::Both;
    double fa[D];
    out.i5 = fa_i5<D>(F, a, fa);
    FibreFrame<D> fr;
    if (reads_i4) {
        fr = FibreFrame<D>(F, a);
        out.i4 = fr.i4;
    }
    const FibreDerivs d = energy.template fibre<D>(out.i4, out.i5);
    out.psi = d.psi;
    if (!std::isfinite(d.psi)) return out;
    double g5[N];
    for (int k = 0; k < N; ++k) g5[k] = 2.0 * fa[k % D] * a[k / D];
    bool i4_terms = reads_i4 && (d.d4 != 0.0 || d.d44 != 0.0 || d.d45 != 0.0);
    if (!i4_terms) {
        out.path = FibrePath::ClosedI5;
        for (int k = 0; k < N; ++k) out.grad[k] = mul0(d.d5, g5[k]);
        if (want_hessian) {
            const double lam[3] = {2.0 * d.d5 + mul0(4.0 * d.d55, out.i5), 2.0 * d.d5, 0.0};
            for (int k = 0; k < 3; ++k) closed[k] = filter.apply(lam[k]);
            unit_fa<D>(fa, n);
        }
        return out;
    }
    out.path = FibrePath::Numeric;
    double gm[D][D], g4[N];
    fr.grad4_m(gm);
    fr.to_f(gm, g4);
    for (int k = 0; k < N; ++k) out.grad[k] = mul0(d.d4, g4[k]) + mul0(d.d5, g5[k]);
    if (want_hessian) {
        double raw[N][N];
        fibre_raw_hessian<D>(fr, a, d, g4, g5, raw);
        project_psd<N>(raw, filter, out.hess);
    }
    return out;
}

/// x-space vectors w_n of an element (fibre/element.rs eq. E1): row n − 1 of
/// Dm⁻¹ for n ≥ 1 and w_0 = −Σ w_n.
template <int D>
ECC_HOST_DEVICE inline void element_w(const double (&dm_inv)[D][D], double w[D + 1][D]) {
    for (int c = 0; c < D; ++c) {
        double s = 0.0;
        for (int m = 0; m < D; ++m) s += dm_inv[m][c];
        w[0][c] = -s;
        for (int n = 1; n <= D; ++n) w[n][c] = dm_inv[n - 1][c];
    }
}

/// The element Hessian of the closed form without the d²×d² matrix
/// (fibre/element.rs eq. E2), β_n = a · w_n, times the measure.
template <int D>
ECC_HOST_DEVICE inline void closed_element(const double w[D + 1][D], const double (&a)[D],
                                           const double f[3], const double n[D], double m,
                                           double h[D * (D + 1)][D * (D + 1)]) {
    constexpr int K = D + 1, NE = D * K;
    double beta[K];
    for (int k = 0; k < K; ++k) {
        beta[k] = 0.0;
        for (int c = 0; c < D; ++c) beta[k] += a[c] * w[k][c];
    }
    for (int i = 0; i < NE; ++i)
        for (int j = 0; j < NE; ++j) {
            int p = i / D, r = i % D, q = j / D, s = j % D;
            double bb = beta[p] * beta[q];
            double iso;
            if (r == s) {
                double ww = 0.0;
                for (int c = 0; c < D; ++c) ww += w[p][c] * w[q][c];
                iso = mul0(f[2], ww - bb) + mul0(f[1], bb * (1.0 - n[r] * n[r]));
            } else {
                iso = mul0(f[1], -bb * n[r] * n[s]);
            }
            h[i][j] = m * (iso + mul0(f[0], bb * n[r] * n[s]));
        }
}

}  // namespace detail

/// ψ(F) of a fibre energy for the unit fibre `a` (fibre/element.rs
/// `psi_kernel`: the SVD only when ψ reads I4); NaN for a non-finite F.
template <int D, class E>
ECC_HOST_DEVICE inline double fibre_psi_f(const E& energy, const double (&F)[D][D],
                                          const double (&a)[D]) {
    for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j)
            if (!std::isfinite(F[i][j])) return nan();
    constexpr FibreUse uses = E::fibre_uses(D);
    double fa[D];
    double i5 = detail::fa_i5<D>(F, a, fa);
    double i4 = (uses == FibreUse::I4 || uses == FibreUse::Both) ? fibre_invariant4<D>(F, a) : nan();
    return energy.template fibre<D>(i4, i5).psi;
}

/// ψ, I4, I5, vec(∂ψ/∂F) and the `filter`ed d²×d² ∂²ψ/∂f² of a fibre energy
/// at F for the unit rest fibre `a` (fibre/dim.rs `fibre_f`). Outside ψ's
/// domain ψ = +∞ with zero derivatives; a non-finite F gives ψ = NaN and
/// zeros (path Degenerate).
template <int D, class E>
ECC_HOST_DEVICE inline FibreEval<D> fibre_eval_f(const E& energy, const double (&F)[D][D],
                                                 const double (&a)[D], Filter filter,
                                                 bool want_hessian = true) {
    double closed[3] = {0.0, 0.0, 0.0}, n[D] = {};
    FibreEval<D> out = detail::fibre_kernel<D>(energy, F, a, filter, want_hessian, closed, n);
    if (want_hessian && out.path == FibrePath::ClosedI5)
        detail::closed_hessian<D>(closed, a, n, out.hess);
    return out;
}

/// Energy, node-major gradient and filtered Hessian of a fibre energy on a
/// linear element (fibre/dim.rs `fibre_element_eval`), all × the rest
/// measure: ∇ψ_e = |q| Wᵀ vec(∂ψ/∂F), ∇²ψ_e = |q| Wᵀ H W (eq. E1), the
/// closed form through eq. E2.
template <int D, class E>
ECC_HOST_DEVICE inline ElementEval<D*(D + 1)> fibre_eval_element_f(
    const E& energy, const double (&F)[D][D], const double (&dm_inv)[D][D], double measure,
    const double (&a)[D], Filter filter, bool want_hessian = true) {
    constexpr int K = D + 1, NE = D * K;
    double closed[3] = {0.0, 0.0, 0.0}, n[D] = {};
    FibreEval<D> p = detail::fibre_kernel<D>(energy, F, a, filter, want_hessian, closed, n);
    ElementEval<NE> out{};
    out.psi = measure * p.psi;
    double w[K][D];
    detail::element_w<D>(dm_inv, w);
    // (Wᵀ g)[(k, r)] = Σ_c w_k[c] g[(c, r)].
    for (int k = 0; k < K; ++k)
        for (int r = 0; r < D; ++r) {
            double s = 0.0;
            for (int c = 0; c < D; ++c) s += w[k][c] * p.grad[c * D + r];
            out.grad[k * D + r] = s * measure;
        }
    if (!want_hessian || p.path == FibrePath::Degenerate) return out;
    if (p.path == FibrePath::ClosedI5) {
        detail::closed_element<D>(w, a, closed, n, measure, out.hess);
        return out;
    }
    double hw[D * D][NE];  // H W
    for (int i = 0; i < D * D; ++i)
        for (int j = 0; j < NE; ++j) {
            int k = j / D, r = j % D;
            double s = 0.0;
            for (int c = 0; c < D; ++c) s += p.hess[i][c * D + r] * w[k][c];
            hw[i][j] = s;
        }
    double h[NE][NE];
    for (int i = 0; i < NE; ++i)
        for (int j = 0; j < NE; ++j) {
            int k = i / D, r = i % D;
            double s = 0.0;
            for (int c = 0; c < D; ++c) s += w[k][c] * hw[c * D + r][j];
            h[i][j] = s * measure;
        }
    // ∞ − ∞ (a raw Hessian at a pole σ_i + σ_j = 0) is reported as +∞, as at F.
    for (int i = 0; i < NE; ++i)
        for (int j = 0; j < NE; ++j) {
            double v = 0.5 * (h[i][j] + h[j][i]);
            out.hess[i][j] = std::isnan(v) ? infinity() : v;
        }
    return out;
}

/// The fibre part of a linear triangle (6×6), × its rest area.
template <class E>
ECC_HOST_DEVICE inline ElementEval<6> fibre_eval_tri(const E& energy, const double (&x)[3][2],
                                                     const double (&dm_inv)[2][2], double area,
                                                     const double (&a)[2], Filter filter,
                                                     bool want_hessian = true) {
    double F[2][2];
    tri_f(x, dm_inv, F);
    return fibre_eval_element_f<2>(energy, F, dm_inv, area, a, filter, want_hessian);
}

/// The fibre part of a linear tetrahedron (12×12), × its rest volume.
template <class E>
ECC_HOST_DEVICE inline ElementEval<12> fibre_eval_tet(const E& energy, const double (&x)[4][3],
                                                      const double (&dm_inv)[3][3], double volume,
                                                      const double (&a)[3], Filter filter,
                                                      bool want_hessian = true) {
    double F[3][3];
    tet_f(x, dm_inv, F);
    return fibre_eval_element_f<3>(energy, F, dm_inv, volume, a, filter, want_hessian);
}

}  // namespace ecc

#endif  // ECC_RUNTIME_HPP
