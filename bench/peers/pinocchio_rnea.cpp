// Pinocchio's RNEA on tendyn's expanded tree, timed with the benchmark protocol of
// docs/references.md: every link and pulley a body on a revolute joint about its z axis,
// the joint angles C q + offset, and Q = Cᵀ τ (virtual work: a body's angle moves with the
// joints through its coupling row of C). Reads the file `expanded_tree` writes
// (bench/examples/expanded_tree.rs), checks Q against tendyn's at every state, then prints
// the median ns per call of 51 samples, each a pass over the 1,024 states.
#include <pinocchio/algorithm/rnea-derivatives.hpp>
#include <pinocchio/algorithm/rnea.hpp>
#include <pinocchio/multibody.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <vector>

using pinocchio::SE3;

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
  if (argc < 2) {
    std::cerr << "usage: pinocchio_rnea FILE.tree\n";
    return 2;
  }
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
    SE3 pre;
    double mass;
    Eigen::Vector3d com;
    Eigen::Matrix3d inertia;
  };
  std::vector<Body> body(bodies);
  Eigen::MatrixXd coupling_read(bodies, n);
  Eigen::VectorXd offset_read(bodies);
  std::vector<SE3> post(bodies);
  for (int b = 0; b < bodies; ++b) {
    double parent;
    in >> parent >> offset_read(b);
    body[b].parent = int(parent);
    body[b].pre = read_transform(in);
    post[b] = read_transform(in);
    for (int j = 0; j < n; ++j) in >> coupling_read(b, j);
    in >> body[b].mass >> body[b].com(0) >> body[b].com(1) >> body[b].com(2);
    body[b].inertia = read_matrix(in);
  }
  // Joints are added depth first: Pinocchio's derivative algorithms take a joint's subtree
  // to be the joints that follow it up to its last descendant, and tendyn's body order
  // (links, then pulleys) is not depth first. (RNEA itself does not care; its derivatives
  // disagreed with central differences of it by 1e-3 in the other order.) Joint k is body
  // order[k], so the rows of C and the offsets are taken in that order.
  std::vector<int> order;
  std::vector<std::vector<int>> children(bodies + 1);
  for (int b = 0; b < bodies; ++b) children[body[b].parent + 1].push_back(b);
  std::vector<int> stack(children[0].rbegin(), children[0].rend());
  while (!stack.empty()) {
    const int b = stack.back();
    stack.pop_back();
    order.push_back(b);
    stack.insert(stack.end(), children[b + 1].rbegin(), children[b + 1].rend());
  }
  Eigen::MatrixXd coupling(bodies, n);
  Eigen::VectorXd offset(bodies);
  std::vector<pinocchio::JointIndex> joint(bodies);
  for (int k = 0; k < bodies; ++k) {
    const int b = order[k];
    coupling.row(k) = coupling_read.row(b);
    offset(k) = offset_read(b);
    // The joint frame is the body frame before `post`: the parent's body frame (its joint
    // frame times its post) times `pre`.
    const int p = body[b].parent;
    const pinocchio::JointIndex parent_joint = p < 0 ? 0 : joint[p];
    const SE3 placement = p < 0 ? body[b].pre : post[p] * body[b].pre;
    joint[b] = model.addJoint(parent_joint, pinocchio::JointModelRZ(), placement,
                              "j" + std::to_string(b));
    // Mass properties given in the body frame, moved to the joint frame by `post`.
    const Eigen::Matrix3d& r = post[b].rotation();
    model.appendBodyToJoint(
        joint[b],
        pinocchio::Inertia(body[b].mass, post[b].act(body[b].com), r * body[b].inertia * r.transpose()),
        SE3::Identity());
  }
  pinocchio::Data data(model);
  // The wrench acts on the link, given in its body frame about the point: in the joint
  // frame (the body frame before `post`), about the joint frame's origin.
  std::vector<pinocchio::Force> fext(model.njoints, pinocchio::Force::Zero());
  if (wrench_link >= 0) {
    const SE3& m = post[int(wrench_link)];
    const Eigen::Vector3d f = m.rotation() * force, p = m.act(point);
    fext[joint[int(wrench_link)]] = pinocchio::Force(f, m.rotation() * moment + p.cross(f));
  }
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
