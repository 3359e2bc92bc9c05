//! The generated types (one `include!` per library file).

include!(concat!(env!("OUT_DIR"), "/arap.rs"));
include!(concat!(env!("OUT_DIR"), "/corotational.rs"));
include!(concat!(env!("OUT_DIR"), "/sd2.rs"));
include!(concat!(env!("OUT_DIR"), "/sd3.rs"));
include!(concat!(env!("OUT_DIR"), "/sarap2.rs"));
include!(concat!(env!("OUT_DIR"), "/sarap3.rs"));
include!(concat!(env!("OUT_DIR"), "/mips2.rs"));
include!(concat!(env!("OUT_DIR"), "/stvk.rs"));
include!(concat!(env!("OUT_DIR"), "/neohookean.rs"));
include!(concat!(env!("OUT_DIR"), "/snh.rs"));
include!(concat!(env!("OUT_DIR"), "/ogden.rs"));
include!(concat!(env!("OUT_DIR"), "/ogden2.rs"));
include!(concat!(env!("OUT_DIR"), "/hencky.rs"));
include!(concat!(env!("OUT_DIR"), "/hencky2.rs"));
include!(concat!(env!("OUT_DIR"), "/poly.rs"));
include!(concat!(env!("OUT_DIR"), "/poly2.rs"));
include!(concat!(env!("OUT_DIR"), "/polyneg.rs"));
include!(concat!(env!("OUT_DIR"), "/polyneg2.rs"));
include!(concat!(env!("OUT_DIR"), "/fibre_arap.rs"));
include!(concat!(env!("OUT_DIR"), "/fibre_stvk.rs"));
include!(concat!(env!("OUT_DIR"), "/fibre_fung.rs"));
