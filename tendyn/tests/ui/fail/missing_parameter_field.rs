#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/parametric_finger.ron", outputs(generalized_forces))]
struct Finger {
    m3: f64,
    g: f64,
}

fn main() {}
