use tendyn_spec::random_mechanism::{valid_random_mechanism, Features};
#[test]
fn dbg() {
    let (text, m) = valid_random_mechanism(7, Features { coupled_pulleys: true, endless: false });
    std::fs::write("/tmp/dbg/r7.ron", &text).unwrap();
    let mut s = tendyn_core::Solver::new(&m);
    let q = vec![0.3; m.dof]; let qd = vec![0.5; m.dof]; let qdd = vec![1.0; m.dof];
    let id = s.inverse_dynamics(&q, &qd, &qdd).unwrap();
    let rows = s.last_balance_rows();
    let qe = s.generalized_forces(&q, &qd, &qdd).unwrap();
    println!("Q tension {:?}\nQ expanded {:?}", id.generalized_forces, qe);
    println!("x {:?}", id.unknowns);
    for r in rows { println!("row const {} coefs {:?}", r.constant, &r.coefficients[..r.n]); }
}
