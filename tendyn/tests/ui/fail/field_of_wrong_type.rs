#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/parametric_finger.ron", outputs(gravity))]
struct Finger {
    m3: f64,
    i3zz: f64,
    g: f32,
    i8: f64,
}

fn main() {}
