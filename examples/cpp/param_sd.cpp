// Surface parameterisation with an ecc-emitted C++ header: symmetric
// Dirichlet (energies/psi/sd2.psi) minimised over the uv map of a disk-
// topology triangle mesh by projected Newton with Eigen's SimplicialLLT —
// the same problem as `ecc sim scenes/camelhead_sd.toml` (runtime/fem/src/param.rs):
//
//   1. each triangle in its own isometric 2D rest frame (Dm, Dm⁻¹, area);
//   2. the mesh scaled to unit total area, so the energy is the area mean;
//   3. start: uniform Tutte embedding (boundary on the unit circle by arc
//      length), rescaled so the uv area equals the rest area;
//   4. projected Newton: per-triangle energy, gradient and PSD-projected 6×6
//      Hessian from `ecc::energies::Sd2::eval_tri` (Filter::clamp()), a tiny
//      diagonal shift for the rigid-motion null space, a step limited to 0.9 of
//      the first triangle flip (SD is a barrier), Armijo backtracking; stop
//      at ‖∇E‖∞ ≤ 1e-4.
//
// Build and run: see README.md in this folder (`make run`).
#include "sd2.hpp"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

using Vec = Eigen::VectorXd;
using SpMat = Eigen::SparseMatrix<double>;

struct Mesh {
    std::vector<std::array<double, 3>> p;
    std::vector<std::array<int, 3>> t;
};

static bool read_off(const std::string& path, Mesh& m) {
    std::ifstream in(path);
    std::string head;
    int nv = 0, nf = 0, ne = 0;
    if (!(in >> head >> nv >> nf >> ne) || head != "OFF") return false;
    m.p.resize(nv);
    for (auto& v : m.p)
        if (!(in >> v[0] >> v[1] >> v[2])) return false;
    for (int f = 0; f < nf; ++f) {
        int k = 0;
        std::array<int, 3> tri{};
        if (!(in >> k >> tri[0] >> tri[1] >> tri[2]) || k != 3) return false;
        m.t.push_back(tri);
    }
    return true;
}

/// Rest data of one triangle in its isometric frame (ecc TriRest::from_3d).
struct Rest {
    double dm_inv[2][2];
    double area;
};

static Rest rest_of(const std::array<double, 3>& a, const std::array<double, 3>& b,
                    const std::array<double, 3>& c) {
    double e1[3], e2[3];
    for (int k = 0; k < 3; ++k) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
    }
    double cr[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0]};
    double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    double det = std::sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
    double dm[2][2] = {{l1, (e1[0] * e2[0] + e1[1] * e2[1] + e1[2] * e2[2]) / l1},
                       {0.0, det / l1}};
    Rest r;
    r.dm_inv[0][0] = dm[1][1] / det;
    r.dm_inv[0][1] = -dm[0][1] / det;
    r.dm_inv[1][0] = -dm[1][0] / det;
    r.dm_inv[1][1] = dm[0][0] / det;
    r.area = 0.5 * det;
    return r;
}

/// Uniform Tutte embedding: boundary loop on the unit circle by arc length,
/// every interior vertex the average of its neighbours.
static Vec tutte(const Mesh& m) {
    const int n = static_cast<int>(m.p.size());
    std::map<std::pair<int, int>, int> edges;
    for (auto& t : m.t)
        for (int k = 0; k < 3; ++k) edges[{t[k], t[(k + 1) % 3]}] += 1;
    std::vector<int> next(n, -1);
    for (auto& [e, c] : edges)
        if (!edges.count({e.second, e.first})) next[e.first] = e.second;
    int start = -1;
    for (int v = 0; v < n && start < 0; ++v)
        if (next[v] >= 0) start = v;
    std::vector<int> loop{start};
    for (int v = next[start]; v != start; v = next[v]) loop.push_back(v);
    std::vector<double> arc(loop.size() + 1, 0.0);
    for (size_t k = 0; k < loop.size(); ++k) {
        auto& a = m.p[loop[k]];
        auto& b = m.p[loop[(k + 1) % loop.size()]];
        arc[k + 1] = arc[k] + std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                                        (a[2] - b[2]) * (a[2] - b[2]));
    }
    Vec uv = Vec::Zero(2 * n);
    std::vector<bool> fixed(n, false);
    for (size_t k = 0; k < loop.size(); ++k) {
        double th = 2.0 * M_PI * arc[k] / arc.back();
        uv[2 * loop[k]] = std::cos(th);
        uv[2 * loop[k] + 1] = std::sin(th);
        fixed[loop[k]] = true;
    }
    std::vector<int> id(n, -1);
    int ni = 0;
    for (int v = 0; v < n; ++v)
        if (!fixed[v]) id[v] = ni++;
    std::vector<Eigen::Triplet<double>> trip;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(ni, 2);
    for (auto& [e, c] : edges) {
        int i = e.first, j = e.second;
        if (!edges.count({j, i}) || i < j) {
            // each undirected edge once, both directions
            for (auto [a, b] : {std::pair<int, int>{i, j}, std::pair<int, int>{j, i}}) {
                if (fixed[a]) continue;
                trip.emplace_back(id[a], id[a], 1.0);
                if (fixed[b]) {
                    rhs(id[a], 0) += uv[2 * b];
                    rhs(id[a], 1) += uv[2 * b + 1];
                } else {
                    trip.emplace_back(id[a], id[b], -1.0);
                }
            }
        }
    }
    SpMat L(ni, ni);
    L.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLLT<SpMat> llt(L);
    Eigen::MatrixXd x = llt.solve(rhs);
    for (int v = 0; v < n; ++v)
        if (!fixed[v]) {
            uv[2 * v] = x(id[v], 0);
            uv[2 * v + 1] = x(id[v], 1);
        }
    return uv;
}

static double signed_area(const Vec& uv, const std::array<int, 3>& t) {
    double ax = uv[2 * t[1]] - uv[2 * t[0]], ay = uv[2 * t[1] + 1] - uv[2 * t[0] + 1];
    double bx = uv[2 * t[2]] - uv[2 * t[0]], by = uv[2 * t[2] + 1] - uv[2 * t[0] + 1];
    return 0.5 * (ax * by - ay * bx);
}

struct Problem {
    Mesh mesh;
    std::vector<Rest> rest;
    ecc::energies::Sd2 sd;

    void nodes(const Vec& uv, const std::array<int, 3>& t, double (&x)[3][2]) const {
        for (int k = 0; k < 3; ++k) {
            x[k][0] = uv[2 * t[k]];
            x[k][1] = uv[2 * t[k] + 1];
        }
    }

    /// Σ |q| Ψ(J_q); +∞ if a triangle is flipped or degenerate.
    double energy(const Vec& uv) const {
        double e = 0.0;
        for (size_t q = 0; q < mesh.t.size(); ++q) {
            if (!(signed_area(uv, mesh.t[q]) > 0.0)) return ecc::infinity();
            double x[3][2];
            nodes(uv, mesh.t[q], x);
            e += rest[q].area * sd.psi_f(jacobian(x, rest[q]));
        }
        return e;
    }

    using Mat2 = double[2][2];
    static const Mat2& jacobian(const double (&x)[3][2], const Rest& r) {
        static thread_local double f[2][2];
        ecc::tri_f(x, r.dm_inv, f);
        return f;
    }

    /// Energy, gradient and projected Hessian (clamp filter).
    double assemble(const Vec& uv, Vec& g, SpMat& H) const {
        const int n2 = static_cast<int>(uv.size());
        g = Vec::Zero(n2);
        std::vector<Eigen::Triplet<double>> trip;
        trip.reserve(mesh.t.size() * 36 + n2);
        double e = 0.0;
        for (size_t q = 0; q < mesh.t.size(); ++q) {
            const auto& t = mesh.t[q];
            double x[3][2];
            nodes(uv, t, x);
            ecc::ElementEval<6> r = sd.eval_tri(x, rest[q].dm_inv, rest[q].area, ecc::Filter::clamp());
            e += r.psi;
            for (int a = 0; a < 6; ++a) {
                int ga = 2 * t[a / 2] + a % 2;
                g[ga] += r.grad[a];
                for (int b = 0; b < 6; ++b) trip.emplace_back(ga, 2 * t[b / 2] + b % 2, r.hess[a][b]);
            }
        }
        H.resize(n2, n2);
        H.setFromTriplets(trip.begin(), trip.end());
        return e;
    }

    /// The largest step keeping every triangle's signed area positive (∞ if none flips).
    double max_step(const Vec& uv, const Vec& d) const {
        double best = ecc::infinity();
        for (auto& t : mesh.t) {
            // 2·A(α) = c + b α + a α² for the uv triangle moved by α d.
            double ux = uv[2 * t[1]] - uv[2 * t[0]], uy = uv[2 * t[1] + 1] - uv[2 * t[0] + 1];
            double vx = uv[2 * t[2]] - uv[2 * t[0]], vy = uv[2 * t[2] + 1] - uv[2 * t[0] + 1];
            double dux = d[2 * t[1]] - d[2 * t[0]], duy = d[2 * t[1] + 1] - d[2 * t[0] + 1];
            double dvx = d[2 * t[2]] - d[2 * t[0]], dvy = d[2 * t[2] + 1] - d[2 * t[0] + 1];
            double c = ux * vy - uy * vx;
            double b = ux * dvy + dux * vy - uy * dvx - duy * vx;
            double a = dux * dvy - duy * dvx;
            double roots[2];
            int nr = 0;
            if (std::fabs(a) < 1e-300) {
                if (b < 0.0) roots[nr++] = -c / b;
            } else {
                double disc = b * b - 4.0 * a * c;
                if (disc >= 0.0) {
                    double s = std::sqrt(disc);
                    double q = -0.5 * (b + std::copysign(s, b));
                    roots[nr++] = q / a;
                    if (q != 0.0) roots[nr++] = c / q;
                }
            }
            for (int k = 0; k < nr; ++k)
                if (roots[k] > 0.0) best = std::min(best, roots[k]);
        }
        return best;
    }
};

int main(int argc, char** argv) {
    const std::string path = argc > 1 ? argv[1] : "../../data/camelhead.off";
    Problem pb;
    if (!read_off(path, pb.mesh)) {
        std::fprintf(stderr, "cannot read the OFF mesh %s\n", path.c_str());
        return 2;
    }
    // Unit total area (the energy is then the area-weighted mean).
    double area = 0.0;
    for (auto& t : pb.mesh.t) area += rest_of(pb.mesh.p[t[0]], pb.mesh.p[t[1]], pb.mesh.p[t[2]]).area;
    const double s = 1.0 / std::sqrt(area);
    for (auto& p : pb.mesh.p)
        for (double& c : p) c *= s;
    double rest_area = 0.0;
    for (auto& t : pb.mesh.t) {
        pb.rest.push_back(rest_of(pb.mesh.p[t[0]], pb.mesh.p[t[1]], pb.mesh.p[t[2]]));
        rest_area += pb.rest.back().area;
    }
    auto t0 = std::chrono::steady_clock::now();
    Vec uv = tutte(pb.mesh);
    double uv_area = 0.0;
    for (auto& t : pb.mesh.t) uv_area += signed_area(uv, t);
    uv *= std::sqrt(rest_area / uv_area);

    const double tol = argc > 2 ? std::atof(argv[2]) : 1e-4;
    Vec g;
    SpMat H;
    Eigen::SimplicialLLT<SpMat> llt;
    double e = pb.assemble(uv, g, H);
    std::printf("vertices %zu triangles %zu initial_energy %.12f\n", pb.mesh.p.size(), pb.mesh.t.size(),
                e / rest_area);
    int it = 0;
    for (; it < 500 && g.lpNorm<Eigen::Infinity>() / rest_area > tol; ++it) {
        double shift = 1e-10 * H.diagonal().mean();
        SpMat I(H.rows(), H.cols());
        I.setIdentity();
        if (it == 0) llt.analyzePattern(H);
        for (int k = 0; k < 12; ++k, shift *= 10.0) {
            llt.factorize(H + shift * I);
            if (llt.info() == Eigen::Success) break;
        }
        Vec d = llt.solve(-g);
        double alpha = std::min(1.0, 0.9 * pb.max_step(uv, d));
        const double slope = g.dot(d);
        double e_new = pb.energy(uv + alpha * d);
        while (!(e_new <= e + 1e-4 * alpha * slope) && alpha > 1e-12) {
            alpha *= 0.5;
            e_new = pb.energy(uv + alpha * d);
        }
        uv += alpha * d;
        e = pb.assemble(uv, g, H);
        std::printf("iter %3d energy %.12f grad_inf %.3e step %.3e\n", it + 1, e / rest_area,
                    g.lpNorm<Eigen::Infinity>() / rest_area, alpha);
    }
    double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int flipped = 0;
    for (auto& t : pb.mesh.t) flipped += signed_area(uv, t) > 0.0 ? 0 : 1;
    std::printf("final_energy %.12f iterations %d grad_inf %.3e flipped %d seconds %.3f\n", e / rest_area, it,
                g.lpNorm<Eigen::Infinity>() / rest_area, flipped, secs);
    return g.lpNorm<Eigen::Infinity>() / rest_area <= tol && flipped == 0 ? 0 : 1;
}
