//! Geometry shared by several schemes and operators: one implementation
//! each, called by all of them.

pub mod crossing;
