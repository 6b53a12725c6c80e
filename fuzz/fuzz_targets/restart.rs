//! The restart reader on arbitrary bytes (2D and 3D files): a checkpoint
//! or an error, never a panic or a huge allocation from a corrupt count.
#![no_main]

use ctc_engine::solve::restart::RestartFile;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(file) = RestartFile::<2>::decode(data) {
        // what decodes re-encodes, and decodes again to the same bytes
        // (bytes, not values: a corrupt file may hold NaNs)
        let bytes = file.encode();
        let again = RestartFile::<2>::decode(&bytes).expect("re-encoded file decodes");
        assert_eq!(again.encode(), bytes);
    }
    let _ = RestartFile::<3>::decode(data);
});
