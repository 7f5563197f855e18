//! What a case is, before anything runs: its declaration (`case.yaml`: requirement, scenes,
//! series, checks) and the lint that every case must pass, the broken cases that fail them,
//! the repository they live in; how a check is evaluated on the data a run gives back and
//! what its result means (the verdict, the row every table shows), with the GCI rule of the
//! convergence checks, the validation budget of the checks against measurements and the
//! measurements a validation case declares it does not compare.

pub mod broken;
pub mod case;
pub mod check;
pub mod check_row;
pub mod csv_columns;
pub mod gci;
pub mod history_csv;
pub mod lint;
pub mod measure_error;
pub mod not_compared;
pub mod other_code_reference;
pub mod profile_gap;
pub mod repo;
pub mod run_data;
pub mod validation;
pub mod verdict;
