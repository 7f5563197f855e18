//! The element kernels and their assembly: the linear-elastic stiffness product
//! ([`stiffness`]), the batched kernels ([`batch`]) and the elastic screen
//! ([`elastic_screen`]), and the scatter of element forces into nodal forces ([`assembly`],
//! [`row_batches`]) on a team of threads ([`workers`]) of a bounded size ([`thread_count`]),
//! or on one thread while the team is measured slower ([`fallback`]).

pub mod assembly;
pub mod batch;
pub mod elastic_screen;
pub mod fallback;
pub mod row_batches;
pub mod stiffness;
pub mod thread_count;
pub mod workers;
