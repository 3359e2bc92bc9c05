// ecc_eigen.hpp — optional adapter between Eigen and the ecc C++ runtime.
//
// Include after an emitted energy header (or ecc_runtime.hpp) when Eigen 3
// is available (Debian: libeigen3-dev; compile with -I/usr/include/eigen3).
// Converts Eigen matrices to the runtime's fixed-size arrays and results
// back to Eigen types; nothing here is needed by the runtime itself.
#ifndef ECC_EIGEN_HPP
#define ECC_EIGEN_HPP

#ifndef ECC_RUNTIME_HPP
#error "include an ecc-emitted header (or ecc_runtime.hpp) before ecc_eigen.hpp"
#endif

#include <Eigen/Core>

namespace ecc {
namespace eigen {

/// F as an array (row-major `a[row][col]`).
template <int D>
inline void to_array(const Eigen::Matrix<double, D, D>& m, double (&a)[D][D]) {
    for (int i = 0; i < D; ++i)
        for (int j = 0; j < D; ++j) a[i][j] = m(i, j);
}

/// ψ, gradient and Hessian of a runtime result (N entries) into its Eigen twin.
template <int N, class R, class Out>
inline void copy_result(const R& r, Out& out) {
    out.psi = r.psi;
    for (int i = 0; i < N; ++i) {
        out.grad(i) = r.grad[i];
        for (int j = 0; j < N; ++j) out.hess(i, j) = r.hess[i][j];
    }
}

/// F = Ds Dm⁻¹ of a linear element, Ds = [x1 − x0, …] (one column per node).
template <int D>
inline Eigen::Matrix<double, D, D> element_f(const Eigen::Matrix<double, D, D + 1>& x,
                                             const Eigen::Matrix<double, D, D>& dm_inv) {
    Eigen::Matrix<double, D, D> ds;
    for (int k = 0; k < D; ++k) ds.col(k) = x.col(k + 1) - x.col(0);
    return ds * dm_inv;
}

/// Ψ, vec(∂Ψ/∂F) (column-major, as Eigen's own storage) and the filtered Hessian.
template <int D>
struct PointEvalE {
    double psi;
    Eigen::Matrix<double, D * D, 1> grad;
    Eigen::Matrix<double, D * D, D * D> hess;
};

/// `energy.eval(F, filter)` with Eigen in and out.
template <int D, class E>
inline PointEvalE<D> eval(const E& energy, const Eigen::Matrix<double, D, D>& F,
                          Filter filter = Filter::clamp()) {
    double a[D][D];
    to_array<D>(F, a);
    PointEval<D> r = eval_f<D>(energy, a, filter);
    PointEvalE<D> out;
    copy_result<D * D>(r, out);
    return out;
}

/// Element energy, gradient and Hessian (node-major) from Eigen data: `x`
/// has one column per node, `dm_inv` is the rest Dm⁻¹.
template <int D>
struct ElementEvalE {
    double psi;
    Eigen::Matrix<double, D*(D + 1), 1> grad;
    Eigen::Matrix<double, D*(D + 1), D*(D + 1)> hess;
};

template <int D, class E>
inline ElementEvalE<D> eval_element(const E& energy, const Eigen::Matrix<double, D, D + 1>& x,
                                    const Eigen::Matrix<double, D, D>& dm_inv, double measure,
                                    Filter filter = Filter::clamp(), bool want_hessian = true) {
    constexpr int N = D * (D + 1);
    const Eigen::Matrix<double, D, D> fm = element_f<D>(x, dm_inv);
    double f[D][D], di[D][D];
    to_array<D>(fm, f);
    to_array<D>(dm_inv, di);
    ElementEval<N> r = eval_element_f<D>(energy, f, di, measure, filter, want_hessian);
    ElementEvalE<D> out;
    copy_result<N>(r, out);
    return out;
}

/// The fibre part at F (`energy.fibre_eval(F, a, filter)`) with Eigen in
/// and out: ψ, I4, I5, vec(∂ψ/∂F) (column-major) and the filtered Hessian.
template <int D>
struct FibreEvalE {
    double psi;
    double i4;
    double i5;
    Eigen::Matrix<double, D * D, 1> grad;
    Eigen::Matrix<double, D * D, D * D> hess;
    FibrePath path;
};

/// `energy.fibre_eval(F, a, filter)` for a unit rest fibre `a`.
template <int D, class E>
inline FibreEvalE<D> fibre_eval(const E& energy, const Eigen::Matrix<double, D, D>& F,
                                const Eigen::Matrix<double, D, 1>& a,
                                Filter filter = Filter::clamp()) {
    double fa[D][D], av[D];
    to_array<D>(F, fa);
    for (int i = 0; i < D; ++i) av[i] = a(i);
    FibreEval<D> r = fibre_eval_f<D>(energy, fa, av, filter);
    FibreEvalE<D> out;
    copy_result<D * D>(r, out);
    out.i4 = r.i4;
    out.i5 = r.i5;
    out.path = r.path;
    return out;
}

/// The fibre part of an element (as `eval_element`) for a unit rest fibre `a`.
template <int D, class E>
inline ElementEvalE<D> fibre_eval_element(const E& energy, const Eigen::Matrix<double, D, D + 1>& x,
                                          const Eigen::Matrix<double, D, D>& dm_inv, double measure,
                                          const Eigen::Matrix<double, D, 1>& a,
                                          Filter filter = Filter::clamp(), bool want_hessian = true) {
    constexpr int N = D * (D + 1);
    const Eigen::Matrix<double, D, D> fm = element_f<D>(x, dm_inv);
    double f[D][D], di[D][D], av[D];
    to_array<D>(fm, f);
    to_array<D>(dm_inv, di);
    for (int i = 0; i < D; ++i) av[i] = a(i);
    ElementEval<N> r = fibre_eval_element_f<D>(energy, f, di, measure, av, filter, want_hessian);
    ElementEvalE<D> out;
    copy_result<N>(r, out);
    return out;
}

}  // namespace eigen
}  // namespace ecc

#endif  // ECC_EIGEN_HPP
