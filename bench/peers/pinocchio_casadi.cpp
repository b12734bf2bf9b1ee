// Pinocchio's RNEA run on CasADi's symbolic scalar (`casadi::SX`) over tendyn's expanded
// tree, and the expression CasADi builds generated as C: the "Pinocchio + CasADi" of issue 16
// and docs/references.md, on this repository's own mechanisms. The tree, the joint angles
// `θ = C q + offset`, the external wrench and `Q = Cᵀ τ` are those of `pinocchio_rnea.cpp`
// (same file, same placement rules). Writes DIR/NAME_casadi.c (CasADi's code generator) and
// DIR/NAME.states (the states and tendyn's Q, for `casadi_time.c`), and prints CasADi's
// operation count, counted as tendyn counts its own: additions, subtractions,
// multiplications, divisions and negations (CasADi's `sq` and `twice` count as one
// multiplication each), sines and cosines apart, inputs, outputs and constants not at all.
#include <pinocchio/autodiff/casadi.hpp>
// (CasADi's scalar must be declared to Pinocchio before the algorithms.)
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/multibody.hpp>

#include <chrono>
#include <fstream>
#include <iostream>
#include <map>
#include <vector>

using pinocchio::SE3;
using SX = casadi::SX;

static Eigen::Matrix3d read_matrix(std::istream& in) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) in >> m(r, c);
  return m;
}

static SE3 read_transform(std::istream& in) {
  Eigen::Matrix3d r = read_matrix(in);
  Eigen::Vector3d t;
  in >> t(0) >> t(1) >> t(2);
  return SE3(r, t);
}

int main(int argc, char** argv) {
  if (argc < 4) {
    std::cerr << "usage: pinocchio_casadi FILE.tree NAME DIR\n";
    return 2;
  }
  const std::string name = argv[2], dir = argv[3];
  std::ifstream in(argv[1]);
  double nd, bd;
  Eigen::Vector3d g;
  in >> nd >> bd >> g(0) >> g(1) >> g(2);
  const int n = int(nd), bodies = int(bd);
  double wrench_link;
  Eigen::Vector3d point, force, moment;
  in >> wrench_link;
  if (wrench_link >= 0) {
    in >> point(0) >> point(1) >> point(2) >> force(0) >> force(1) >> force(2) >> moment(0) >>
        moment(1) >> moment(2);
  }
  pinocchio::Model model;
  model.gravity.linear(g);
  struct Body {
    int parent;
    SE3 pre, post;
    double mass, offset;
    Eigen::Vector3d com;
    Eigen::Matrix3d inertia;
    Eigen::VectorXd coupling;
  };
  std::vector<Body> body(bodies);
  for (Body& b : body) {
    double parent;
    in >> parent >> b.offset;
    b.parent = int(parent);
    b.pre = read_transform(in);
    b.post = read_transform(in);
    b.coupling.resize(n);
    for (int j = 0; j < n; ++j) in >> b.coupling(j);
    in >> b.mass >> b.com(0) >> b.com(1) >> b.com(2);
    b.inertia = read_matrix(in);
  }
  // Bodies in file order: RNEA does not need a depth-first order (pinocchio_rnea.cpp adds
  // them depth first for its derivative algorithms only). A parent precedes its children.
  std::vector<pinocchio::JointIndex> joint(bodies);
  for (int b = 0; b < bodies; ++b) {
    const int p = body[b].parent;
    const SE3 placement = p < 0 ? body[b].pre : body[p].post * body[b].pre;
    joint[b] = model.addJoint(p < 0 ? 0 : joint[p], pinocchio::JointModelRZ(), placement,
                              "j" + std::to_string(b));
    const Eigen::Matrix3d& r = body[b].post.rotation();
    model.appendBodyToJoint(joint[b],
                            pinocchio::Inertia(body[b].mass, body[b].post.act(body[b].com),
                                               r * body[b].inertia * r.transpose()),
                            SE3::Identity());
  }

  const auto t0 = std::chrono::steady_clock::now();
  using ADModel = pinocchio::ModelTpl<SX>;
  ADModel ad_model = model.cast<SX>();
  ADModel::Data ad_data(ad_model);
  SX q = SX::sym("q", n), qd = SX::sym("qd", n), qdd = SX::sym("qdd", n);
  ADModel::ConfigVectorType theta(bodies), rate(bodies), accel(bodies);
  for (int b = 0; b < bodies; ++b) {
    const pinocchio::JointIndex k = joint[b];
    // Joint k's coordinate is index k − 1 of Pinocchio's configuration (the universe is 0).
    SX angle = body[b].offset, w = 0, wd = 0;
    for (int j = 0; j < n; ++j) {
      const double c = body[b].coupling(j);
      if (c == 0) continue;
      angle += c * q(j);
      w += c * qd(j);
      wd += c * qdd(j);
    }
    theta[ad_model.joints[k].idx_q()] = angle;
    rate[ad_model.joints[k].idx_v()] = w;
    accel[ad_model.joints[k].idx_v()] = wd;
  }
  PINOCCHIO_ALIGNED_STD_VECTOR(pinocchio::ForceTpl<SX>) fext(ad_model.njoints,
                                                             pinocchio::ForceTpl<SX>::Zero());
  if (wrench_link >= 0) {
    const SE3& m = body[int(wrench_link)].post;
    const Eigen::Vector3d f = m.rotation() * force, p = m.act(point);
    const pinocchio::Force w(f, m.rotation() * moment + p.cross(f));
    fext[joint[int(wrench_link)]] = w.cast<SX>();
  }
  pinocchio::rnea(ad_model, ad_data, theta, rate, accel, fext);
  SX generalized = SX::zeros(n);
  for (int j = 0; j < n; ++j) {
    SX sum = 0;
    for (int b = 0; b < bodies; ++b) {
      const double c = body[b].coupling(j);
      if (c != 0) sum += c * ad_data.tau[ad_model.joints[joint[b]].idx_v()];
    }
    generalized(j) = sum;
  }
  // As Pinocchio's expression comes, and with CasADi's common subexpression elimination
  // (its `cse` option, which a user generating code would turn on): both are generated and
  // timed.
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
  gen.add(plain);
  gen.add(merged);
  gen.generate(dir + "/");
  const double generated_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
  std::cout << name << ": traced and built in " << built_ms << " ms, C written in "
            << generated_ms << " ms\n";

  // The states, in tendyn's coordinates, with tendyn's Q, for the timing driver.
  std::ofstream states(dir + "/" + name + ".states");
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
