//! What a validated scene will cost, estimated before anything is allocated: elements, time
//! steps, history rows and memory ([`budget`]), a time step that makes no run ([`time_step`]),
//! and what both are made of ([`measures`]).

pub mod budget;
pub mod measures;
pub mod time_step;
