//! Tests of the figures that look inside them: the rays they record, the scenes and
//! cameras of their pictures.

mod camera_side;
mod figure_details;
mod figures;
mod rendered;
