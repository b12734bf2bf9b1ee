// tendyn's expanded tree as a Pinocchio model, read from the file that
// bench/examples/expanded_tree.rs writes: one reader for both harnesses
// (pinocchio_rnea.cpp, pinocchio_casadi.cpp). Every link and pulley is a body on a revolute
// joint about its own z axis, placed as tendyn places it (paper Eq. 8: `pre · RotZ(θ) · post`
// in its parent's frame; Pinocchio's joint frame is the body frame before `post`), with the
// joint angles `θ = C q + offset`. The stream is left at the first state. A file that cannot be
// read, or whose parents do not form a tree, throws std::runtime_error.
#pragma once

#include <pinocchio/multibody.hpp>

#include <fstream>
#include <iostream>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

struct ExpandedTree {
  int dof = 0, bodies = 0;
  pinocchio::Model model;
  // Joint k is body order[k]; body b's joint is joint[b].
  std::vector<int> order;
  std::vector<pinocchio::JointIndex> joint;
  // C and the offsets, a row per joint in joint order.
  Eigen::MatrixXd coupling;
  Eigen::VectorXd offset;
  // The external wrench, per joint, in the joint frame about its origin.
  std::vector<pinocchio::Force> fext;
};

inline Eigen::Matrix3d read_matrix(std::istream& in) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) in >> m(r, c);
  return m;
}

inline pinocchio::SE3 read_transform(std::istream& in) {
  Eigen::Matrix3d r = read_matrix(in);
  Eigen::Vector3d t;
  in >> t(0) >> t(1) >> t(2);
  return pinocchio::SE3(r, t);
}

inline ExpandedTree read_expanded_tree(std::istream& in) {
  using pinocchio::SE3;
  ExpandedTree tree;
  double nd, bd;
  Eigen::Vector3d g;
  if (!(in >> nd >> bd >> g(0) >> g(1) >> g(2)) || nd < 1 || bd < nd)
    throw std::runtime_error("no tree header (degrees of freedom, bodies, gravity)");
  const int n = tree.dof = int(nd), bodies = tree.bodies = int(bd);
  double wrench_link;
  Eigen::Vector3d point, force, moment;
  in >> wrench_link;
  if (!in) throw std::runtime_error("no external wrench line");
  if (wrench_link >= bd) throw std::runtime_error("the external wrench's link is not a body");
  if (wrench_link >= 0) {
    in >> point(0) >> point(1) >> point(2) >> force(0) >> force(1) >> force(2) >> moment(0) >>
        moment(1) >> moment(2);
  }
  tree.model.gravity.linear(g);
  struct Body {
    int parent;
    SE3 pre, post;
    double mass;
    Eigen::Vector3d com;
    Eigen::Matrix3d inertia;
  };
  std::vector<Body> body(bodies);
  Eigen::MatrixXd coupling_read(bodies, n);
  Eigen::VectorXd offset_read(bodies);
  for (int b = 0; b < bodies; ++b) {
    double parent;
    in >> parent >> offset_read(b);
    body[b].parent = int(parent);
    body[b].pre = read_transform(in);
    body[b].post = read_transform(in);
    for (int j = 0; j < n; ++j) in >> coupling_read(b, j);
    in >> body[b].mass >> body[b].com(0) >> body[b].com(1) >> body[b].com(2);
    body[b].inertia = read_matrix(in);
    if (!in) throw std::runtime_error("body " + std::to_string(b) + " is incomplete");
    if (body[b].parent < -1 || body[b].parent >= b)
      throw std::runtime_error("body " + std::to_string(b) + " has parent " +
                               std::to_string(body[b].parent) + ", not an earlier body or -1");
  }
  // Joints are added depth first: Pinocchio's derivative algorithms take a joint's subtree
  // to be the joints that follow it up to its last descendant, and tendyn's body order
  // (links, then pulleys) is not depth first. (RNEA itself does not care; its derivatives
  // disagreed with central differences of it by 1e-3 in the other order.) Joint k is body
  // order[k], so the rows of C and the offsets are taken in that order.
  std::vector<std::vector<int>> children(bodies + 1);
  for (int b = 0; b < bodies; ++b) children[body[b].parent + 1].push_back(b);
  std::vector<int> stack(children[0].rbegin(), children[0].rend());
  while (!stack.empty()) {
    const int b = stack.back();
    stack.pop_back();
    tree.order.push_back(b);
    stack.insert(stack.end(), children[b + 1].rbegin(), children[b + 1].rend());
  }
  tree.coupling.resize(bodies, n);
  tree.offset.resize(bodies);
  tree.joint.resize(bodies);
  for (int k = 0; k < bodies; ++k) {
    const int b = tree.order[k];
    tree.coupling.row(k) = coupling_read.row(b);
    tree.offset(k) = offset_read(b);
    // The joint frame is the body frame before `post`: the parent's body frame (its joint
    // frame times its post) times `pre`.
    const int p = body[b].parent;
    const pinocchio::JointIndex parent_joint = p < 0 ? 0 : tree.joint[p];
    const SE3 placement = p < 0 ? body[b].pre : body[p].post * body[b].pre;
    tree.joint[b] = tree.model.addJoint(parent_joint, pinocchio::JointModelRZ(), placement,
                                        "j" + std::to_string(b));
    // Mass properties given in the body frame, moved to the joint frame by `post`.
    const Eigen::Matrix3d& r = body[b].post.rotation();
    tree.model.appendBodyToJoint(tree.joint[b],
                                 pinocchio::Inertia(body[b].mass, body[b].post.act(body[b].com),
                                                    r * body[b].inertia * r.transpose()),
                                 SE3::Identity());
  }
  // The wrench acts on the link, given in its body frame about the point: in the joint
  // frame (the body frame before `post`), about the joint frame's origin.
  tree.fext.assign(tree.model.njoints, pinocchio::Force::Zero());
  if (wrench_link >= 0) {
    const SE3& m = body[int(wrench_link)].post;
    const Eigen::Vector3d f = m.rotation() * force, p = m.act(point);
    tree.fext[tree.joint[int(wrench_link)]] =
        pinocchio::Force(f, m.rotation() * moment + p.cross(f));
  }
  return tree;
}

// Opens the tree file at `path` into `in` and reads it into `tree`, leaving `in` at the
// first state; where it cannot, says why on stderr and returns false.
inline bool open_expanded_tree(const char* path, std::ifstream& in, ExpandedTree& tree) {
  in.open(path);
  try {
    tree = read_expanded_tree(in);
    return true;
  } catch (const std::runtime_error& e) {
    std::cerr << path << ": " << e.what() << "\n";
    return false;
  }
}
