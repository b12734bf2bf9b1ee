// Pinocchio's RNEA on tendyn's expanded tree, timed with the benchmark protocol of
// docs/references.md: every link and pulley a body on a revolute joint about its z axis,
// the joint angles C q + offset, and Q = Cᵀ τ (virtual work: a body's angle moves with the
// joints through its coupling row of C). Reads the file `expanded_tree` writes
// (bench/examples/expanded_tree.rs), checks Q against tendyn's at every state, then prints
// the median ns per call of 51 samples, each a pass over the 1,024 states.
#include <pinocchio/algorithm/rnea-derivatives.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include "expanded_tree.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: pinocchio_rnea FILE.tree\n";
    return 2;
  }
  std::ifstream in;
  ExpandedTree tree;
  if (!open_expanded_tree(argv[1], in, tree)) return 2;
  const int n = tree.dof, bodies = tree.bodies;
  const pinocchio::Model& model = tree.model;
  const Eigen::MatrixXd& coupling = tree.coupling;
  const Eigen::VectorXd& offset = tree.offset;
  const std::vector<pinocchio::Force>& fext = tree.fext;
  pinocchio::Data data(model);
  struct State {
    Eigen::VectorXd q, v, a, tendyn;
    Eigen::MatrixXd d_q, d_qd;  // tendyn's ∂Q/∂q, ∂Q/∂q̇
  };
  std::vector<State> states;
  for (;;) {
    Eigen::VectorXd x(4 * n + 2 * n * n);
    for (int i = 0; i < x.size(); ++i) in >> x(i);
    if (!in) break;
    State s;
    s.q = coupling * x.segment(0, n) + offset;
    s.v = coupling * x.segment(n, n);
    s.a = coupling * x.segment(2 * n, n);
    s.tendyn = x.segment(3 * n, n);
    using RowMajor = Eigen::Matrix<double, -1, -1, Eigen::RowMajor>;
    s.d_q = Eigen::Map<RowMajor>(x.data() + 4 * n, n, n);
    s.d_qd = Eigen::Map<RowMajor>(x.data() + 4 * n + n * n, n, n);
    states.push_back(s);
  }
  // Agreement: max-norm relative error of Q = Cᵀ τ against tendyn's generalized forces.
  double worst = 0;
  for (const State& s : states) {
    Eigen::VectorXd q = coupling.transpose() * pinocchio::rnea(model, data, s.q, s.v, s.a, fext);
    worst = std::max(worst, (q - s.tendyn).lpNorm<Eigen::Infinity>() /
                                std::max(1e-300, s.tendyn.lpNorm<Eigen::Infinity>()));
  }
  // Timing: warm-up, then 51 samples of R passes (R so that a sample lasts >= 2 ms).
  Eigen::VectorXd out(n);
  double sink = 0;
  auto pass = [&]() {
    for (const State& s : states) {
      out.noalias() = coupling.transpose() * pinocchio::rnea(model, data, s.q, s.v, s.a, fext);
      sink += out(0);
    }
  };
  using clock = std::chrono::steady_clock;
  auto t0 = clock::now();
  int r = 0;
  while (std::chrono::duration<double>(clock::now() - t0).count() < 0.3) {
    pass();
    ++r;
  }
  const double per_pass = 0.3 / r;
  const int reps = std::max(1, int(std::ceil(2e-3 / per_pass)));
  std::vector<double> ns;
  for (int k = 0; k < 51; ++k) {
    auto a = clock::now();
    for (int i = 0; i < reps; ++i) pass();
    auto b = clock::now();
    ns.push_back(std::chrono::duration<double, std::nano>(b - a).count() / (reps * states.size()));
  }
  std::nth_element(ns.begin(), ns.begin() + 25, ns.end());
  std::cout << argv[1] << ": Pinocchio rnea, Q = C^T tau: " << ns[25] << " ns per call (median of 51), "
            << states.size() << " states, max relative error against tendyn " << worst
            << " (checksum " << sink << ")\n";
  // Pinocchio's analytical derivatives of RNEA (Carpentier and Mansard, 2018) on the same
  // tree, with Q: ∂Q/∂q = Cᵀ (∂τ/∂θ) C and ∂Q/∂q̇ = Cᵀ (∂τ/∂θ̇) C.
  Eigen::MatrixXd dq(n, n), dqd(n, n);
  auto derivatives = [&](const State& s) {
    pinocchio::computeRNEADerivatives(model, data, s.q, s.v, s.a, fext);
    dq.noalias() = coupling.transpose() * data.dtau_dq * coupling;
    dqd.noalias() = coupling.transpose() * data.dtau_dv * coupling;
    out.noalias() = coupling.transpose() * data.tau;
  };
  double worst_d = 0;
  if (getenv("TENDYN_PEERS_DEBUG")) {
    // Pinocchio's own ∂τ/∂θ against central differences of its rnea.
    const State& s = states[0];
    pinocchio::computeRNEADerivatives(model, data, s.q, s.v, s.a, fext);
    Eigen::MatrixXd analytic = data.dtau_dq, analytic_v = data.dtau_dv;
    Eigen::MatrixXd fd(bodies, bodies), fd_v(bodies, bodies);
    for (int k = 0; k < bodies; ++k) {
      Eigen::VectorXd e = Eigen::VectorXd::Unit(bodies, k) * 1e-6;
      Eigen::VectorXd p = pinocchio::rnea(model, data, s.q + e, s.v, s.a, fext);
      Eigen::VectorXd m = pinocchio::rnea(model, data, s.q - e, s.v, s.a, fext);
      fd.col(k) = (p - m) / 2e-6;
      p = pinocchio::rnea(model, data, s.q, s.v + e, s.a, fext);
      m = pinocchio::rnea(model, data, s.q, s.v - e, s.a, fext);
      fd_v.col(k) = (p - m) / 2e-6;
    }
    std::cout << "pinocchio dtau_dq vs its own FD: " << (fd - analytic).lpNorm<Eigen::Infinity>() / analytic.lpNorm<Eigen::Infinity>()
              << ", dtau_dv: " << (fd_v - analytic_v).lpNorm<Eigen::Infinity>() / analytic_v.lpNorm<Eigen::Infinity>() << "\n";
  }
  for (const State& s : states) {
    derivatives(s);
    const double scale = std::max(
        {1e-300, s.d_q.lpNorm<Eigen::Infinity>(), s.d_qd.lpNorm<Eigen::Infinity>()});
    worst_d = std::max({worst_d, (dq - s.d_q).lpNorm<Eigen::Infinity>() / scale,
                        (dqd - s.d_qd).lpNorm<Eigen::Infinity>() / scale});
  }
  auto pass_d = [&]() {
    for (const State& s : states) {
      derivatives(s);
      sink += dq(0, 0) + dqd(0, 0) + out(0);
    }
  };
  t0 = clock::now();
  r = 0;
  while (std::chrono::duration<double>(clock::now() - t0).count() < 0.3) {
    pass_d();
    ++r;
  }
  const int reps_d = std::max(1, int(std::ceil(2e-3 / (0.3 / r))));
  ns.clear();
  for (int k = 0; k < 51; ++k) {
    auto a = clock::now();
    for (int i = 0; i < reps_d; ++i) pass_d();
    auto b = clock::now();
    ns.push_back(std::chrono::duration<double, std::nano>(b - a).count() /
                 (reps_d * states.size()));
  }
  std::nth_element(ns.begin(), ns.begin() + 25, ns.end());
  std::cout << argv[1] << ": Pinocchio computeRNEADerivatives, (Q, dQ/dq, dQ/dqd): " << ns[25]
            << " ns per call (median of 51), max relative error against tendyn " << worst_d
            << " (checksum " << sink << ")\n";
  return 0;
}
