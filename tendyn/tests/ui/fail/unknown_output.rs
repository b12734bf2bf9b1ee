#[derive(tendyn::TendonMechanism)]
#[tendyn(
    file = "tests/ui/mechanisms/open_ended.ron",
    outputs(generalized_forces, tendon_forces)
)]
struct Arm;

fn main() {}
