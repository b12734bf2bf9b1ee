#[derive(tendyn::TendonMechanism)]
struct Finger;

fn main() {}
