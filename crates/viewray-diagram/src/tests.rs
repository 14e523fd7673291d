//! Tests of the figures that look inside them: the rays they record, the scenes and
//! cameras of their pictures.

mod figures;
mod rendered;
