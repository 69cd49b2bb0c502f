//! The TopMod tools of issue 16 beyond the dissertation's operators: object
//! tools (`object`), wireframe and column modelling (`wireframe`), the
//! multi-face handle (`multi_handle`), rind by scaling, conical cuts
//! (`cut`) and convex hulls (`hull`). Each file says which TopMod function
//! it follows (TopModLab/TopMod, `include/dlflaux/`), that source being
//! their only description.

pub(crate) mod builder;
mod object;
mod wireframe;
mod column;
mod column_repair;
pub mod hull;
mod closest_sides;
mod multi_handle;
mod cut;

pub use column_repair::CheckedColumns;
pub use object::Planarized;
