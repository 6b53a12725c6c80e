//! Build script: with the `meshio` feature, embeds the run-time library
//! path of the Python that pyo3 links against (a pyenv or venv Python is
//! usually not on the loader path), so test binaries start without
//! `LD_LIBRARY_PATH`. Without the feature it does nothing.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    #[cfg(feature = "meshio")]
    {
        let config = pyo3_build_config::get();
        if let Some(dir) = &config.lib_dir {
            println!("cargo:rustc-link-arg=-Wl,-rpath,{dir}");
        }
    }
}
