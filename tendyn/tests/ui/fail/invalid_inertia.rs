#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/invalid_inertia.ron")]
struct Arm;

fn main() {}
