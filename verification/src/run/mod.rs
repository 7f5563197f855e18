//! Running the cases (`impact verify`): their jobs (scene runs and builtin computations,
//! the code-verification builtins among them), the runner that plans, runs and judges them
//! into the matrix and writes it out, its shards across machines, the matrix's own history
//! invariants and the discriminating power of each case's wrong models.

pub mod builtin_params;
pub mod builtins;
pub mod case_progress;
pub mod case_rows;
pub mod code_verification;
pub mod discriminate;
pub mod history_invariants;
pub mod invariant_row;
pub mod job_loop;
pub mod jobs;
pub mod matrix;
pub mod matrix_files;
pub mod other_code;
pub mod plan;
pub mod rigid_plastic;
pub mod runner;
pub mod shard;
pub mod summary_invariants;
pub mod surface_invariants;
pub mod wall_invariants;
