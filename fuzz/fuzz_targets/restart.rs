//! The restart reader on arbitrary bytes (2D and 3D files): a checkpoint
//! or an error, never a panic or a huge allocation from a corrupt count.
#![no_main]

use ctc_engine::solve::restart::RestartFile;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(file) = RestartFile::<2>::decode(data) {
        // what decodes re-encodes to the same bytes
        assert_eq!(RestartFile::<2>::decode(&file.encode()).ok(), Some(file));
    }
    let _ = RestartFile::<3>::decode(data);
});
