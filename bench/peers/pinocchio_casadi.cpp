// Pinocchio's RNEA run on CasADi's symbolic scalar (`casadi::SX`) over tendyn's expanded
// tree, and the expression CasADi builds generated as C: the "Pinocchio + CasADi" of issue 16
// and docs/references.md, on this repository's own mechanisms. The tree, the joint angles
// `θ = C q + offset`, the external wrench and `Q = Cᵀ τ` are those of `pinocchio_rnea.cpp`
// (the same reader, expanded_tree.hpp). Writes DIR/NAME_casadi.c (CasADi's code generator) and
// DIR/NAME.states (the states and tendyn's Q, for `casadi_time.c`), and prints CasADi's
// operation count, counted as tendyn counts its own: additions, subtractions,
// multiplications, divisions and negations (CasADi's `sq` and `twice` count as one
// multiplication each), sines and cosines apart, inputs, outputs and constants not at all.
#include <pinocchio/autodiff/casadi.hpp>
// (CasADi's scalar must be declared to Pinocchio before the algorithms.)
#include <pinocchio/algorithm/rnea.hpp>
#include "expanded_tree.hpp"

#include <chrono>
#include <fstream>
#include <iostream>
#include <map>
#include <vector>

using SX = casadi::SX;

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: pinocchio_casadi FILE.tree NAME DIR\n";
    return 2;
  }
  const std::string name = argv[2], dir = argv[3];
  std::ifstream in;
  ExpandedTree tree;
  if (!open_expanded_tree(argv[1], in, tree)) return 2;
  const int n = tree.dof, bodies = tree.bodies;

  const auto t0 = std::chrono::steady_clock::now();
  using ADModel = pinocchio::ModelTpl<SX>;
  ADModel ad_model = tree.model.cast<SX>();
  ADModel::Data ad_data(ad_model);
  SX q = SX::sym("q", n), qd = SX::sym("qd", n), qdd = SX::sym("qdd", n);
  ADModel::ConfigVectorType theta(bodies);
  ADModel::TangentVectorType rate(bodies), accel(bodies);
  // Joint k (body order[k]) has the k-th row of C and offset; zero coefficients are skipped
  // so that CasADi's expression holds no `0 * q_j` to fold.
  auto joint_of = [&](int k) -> const ADModel::JointModel& {
    return ad_model.joints[tree.joint[tree.order[k]]];
  };
  for (int k = 0; k < bodies; ++k) {
    SX angle = tree.offset(k), w = 0, wd = 0;
    for (int j = 0; j < n; ++j) {
      const double c = tree.coupling(k, j);
      if (c == 0) continue;
      angle += c * q(j);
      w += c * qd(j);
      wd += c * qdd(j);
    }
    theta[joint_of(k).idx_q()] = angle;
    rate[joint_of(k).idx_v()] = w;
    accel[joint_of(k).idx_v()] = wd;
  }
  std::vector<pinocchio::ForceTpl<SX>> fext;
  for (const pinocchio::Force& f : tree.fext) fext.push_back(f.cast<SX>());
  pinocchio::rnea(ad_model, ad_data, theta, rate, accel, fext);
  SX generalized = SX::zeros(n);
  for (int j = 0; j < n; ++j) {
    SX sum = 0;
    for (int k = 0; k < bodies; ++k) {
      const double c = tree.coupling(k, j);
      if (c != 0) sum += c * ad_data.tau[joint_of(k).idx_v()];
    }
    generalized(j) = sum;
  }
  // As Pinocchio's expression comes, and with CasADi's common subexpression elimination
  // (its `cse` option, which a user generating code would turn on): both are counted, and
  // the second is generated and timed. (Generated both, gcc's own elimination and identical
  // code folding made them one machine function.)
  casadi::Function plain("casadi_q", {q, qd, qdd}, {generalized});
  casadi::Function merged("casadi_q_cse", {q, qd, qdd}, {generalized}, {{"cse", true}});
  const double built_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  for (const casadi::Function& f : {plain, merged}) {
    std::map<std::string, long> counts;
    for (casadi_int k = 0; k < f.n_instructions(); ++k) {
      switch (f.instruction_id(k)) {
        case casadi::OP_ADD: case casadi::OP_SUB: counts["add/sub"]++; break;
        case casadi::OP_MUL: case casadi::OP_SQ: case casadi::OP_TWICE: counts["mul"]++; break;
        case casadi::OP_DIV: counts["div"]++; break;
        case casadi::OP_NEG: counts["neg"]++; break;
        case casadi::OP_SIN: counts["sin"]++; break;
        case casadi::OP_COS: counts["cos"]++; break;
        case casadi::OP_CONST: case casadi::OP_INPUT: case casadi::OP_OUTPUT: break;
        default: counts["other"]++; break;
      }
    }
    const long arithmetic = counts["add/sub"] + counts["mul"] + counts["div"] + counts["neg"];
    std::cout << name << ": Pinocchio + CasADi `" << f.name() << "`: " << arithmetic
              << " arithmetic (" << counts["add/sub"] << " add/sub, " << counts["mul"]
              << " mul, " << counts["div"] << " div, " << counts["neg"] << " neg), "
              << counts["sin"] << " sin, " << counts["cos"] << " cos, " << counts["other"]
              << " other\n";
  }
  const auto t1 = std::chrono::steady_clock::now();
  casadi::CodeGenerator gen(name + "_casadi.c");
  gen.add(merged);
  gen.generate(dir + "/");
  const double generated_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
  std::cout << name << ": traced and built in " << built_ms << " ms, C written in "
            << generated_ms << " ms\n";

  // The states, in tendyn's coordinates, with tendyn's Q, for the timing driver.
  std::ofstream states(dir + "/" + name + ".states");
  if (!states) {
    std::cerr << dir << "/" << name << ".states: cannot be written\n";
    return 2;
  }
  states.precision(17);
  states << n << "\n";
  for (;;) {
    Eigen::VectorXd x(4 * n + 2 * n * n);
    for (int i = 0; i < x.size(); ++i) in >> x(i);
    if (!in) break;
    for (int i = 0; i < 4 * n; ++i) states << x(i) << (i + 1 < 4 * n ? ' ' : '\n');
  }
  return 0;
}
