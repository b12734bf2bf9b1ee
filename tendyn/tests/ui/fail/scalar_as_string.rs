#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/open_ended.ron", scalar = "f32")]
struct Arm;

fn main() {}
