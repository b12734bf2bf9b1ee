#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/open_ended.ron", outputs())]
struct Arm;

fn main() {}
