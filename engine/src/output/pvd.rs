//! ParaView collection (`results.pvd`): the time series of VTU files.

use std::fmt::Write;

/// The block (`part`) of a result file in the collection: 0 for the
/// bodies (`inc_NNNN.vtu`), `k + 1` for rigid tool `k`
/// (`tool_<k>_NNNN.vtu`), so ParaView shows each tool as its own block.
pub fn part(file: &str) -> usize {
    file.strip_prefix("tool_")
        .and_then(|r| r.split_once('_'))
        .and_then(|(k, _)| k.parse::<usize>().ok())
        .map_or(0, |k| k + 1)
}

/// The PVD text for `(time, file)` entries.
pub fn pvd(entries: &[(f64, String)]) -> String {
    let mut s = String::new();
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str("<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
    s.push_str("  <Collection>\n");
    for (t, file) in entries {
        let _ = writeln!(
            s,
            "    <DataSet timestep=\"{}\" group=\"\" part=\"{}\" file=\"{file}\"/>",
            super::encode::fmt_f64(*t),
            part(file)
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

    #[test]
    fn tools_are_their_own_blocks() {
        let s = pvd(&[
            (0.5, "inc_0001.vtu".into()),
            (0.5, "tool_0_0001.vtu".into()),
            (0.5, "tool_11_0001.vtu".into()),
        ]);
        assert!(s.contains("part=\"0\" file=\"inc_0001.vtu\""));
        assert!(s.contains("part=\"1\" file=\"tool_0_0001.vtu\""));
        assert!(s.contains("part=\"12\" file=\"tool_11_0001.vtu\""));
    }
}
