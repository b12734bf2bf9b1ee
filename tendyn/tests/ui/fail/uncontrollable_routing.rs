#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/uncontrollable.ron")]
struct Arm;

fn main() {}
