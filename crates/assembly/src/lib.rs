//! The assembly model of apart and its loader (in progress: the loader follows).
