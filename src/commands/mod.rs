//! One module per subcommand.

pub mod batch;
pub mod check;
pub mod decompose;
pub mod disassemble;
pub mod load;
pub mod partition;
pub mod place;
pub mod placement_args;
pub mod separate;
pub mod sequence;
pub mod stack;
