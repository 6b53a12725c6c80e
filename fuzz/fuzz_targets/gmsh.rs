//! The gmsh reader (ASCII 2.2 / 4.1, planar and solid) on arbitrary bytes:
//! a mesh or a located error, never a panic or an allocation failure.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = ctc_engine::mesh::gmsh::parse_bytes(data);
    let _ = ctc_engine::mesh::gmsh::parse_solid_bytes(data);
});
