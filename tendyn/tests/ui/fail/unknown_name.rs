#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/unknown_name.ron")]
struct Arm;

fn main() {}
