//! ParaView collection (`results.pvd`): the time series of VTU files.

use std::fmt::Write;

/// The PVD text for `(time, file)` entries.
pub fn pvd(entries: &[(f64, String)]) -> String {
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str("<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
    s.push_str("  <Collection>\n");
    for (t, file) in entries {
        let _ = writeln!(
            s,
            "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{file}\"/>",
            super::encode::fmt_f64(*t)
        );
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pvd_lists_every_dataset_in_order() {
        let s = pvd(&[(0.5, "inc_0001.vtu".into()), (1.0, "inc_0002.vtu".into())]);
        let a = s.find("timestep=\"0.5\"").unwrap();
        let b = s.find("file=\"inc_0002.vtu\"").unwrap();
        assert!(a < b);
        assert!(s.trim_end().ends_with("</VTKFile>"));
    }
}
