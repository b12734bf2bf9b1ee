#[derive(tendyn::TendonMechanism)]
#[tendyn(
    file = "tests/ui/mechanisms/motor_only.ron",
    outputs(generalized_forces, segment_tensions)
)]
struct Arm;

fn main() {}
