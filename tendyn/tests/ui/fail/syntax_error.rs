#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/syntax_error.ron")]
struct Arm;

fn main() {}
