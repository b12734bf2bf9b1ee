#[derive(tendyn::TendonMechanism)]
#[tendyn(file = "tests/ui/mechanisms/no_such_finger.ron")]
struct Finger;

fn main() {}
