//! Build script: nothing without the `petsc` feature; with it, finds the
//! system PETSc (pkg-config `PETSc`, or `PETSC_DIR` [+ `PETSC_ARCH`]) and
//! METIS, generates the FFI bindings with bindgen and tells which optional
//! PETSc packages the build has (`cfg(petsc_have_hypre)`, `cfg(petsc_have_mumps)`).

fn main() {
    println!("cargo:rustc-check-cfg=cfg(petsc_have_hypre)");
    println!("cargo:rustc-check-cfg=cfg(petsc_have_mumps)");
    #[cfg(feature = "petsc")]
    with_petsc::generate();
}

#[cfg(feature = "petsc")]
mod with_petsc {
    use std::path::{Path, PathBuf};

    /// Include and library directories of PETSc.
    struct Found {
        include: Vec<PathBuf>,
        libs: Vec<PathBuf>,
    }

    fn find_petsc() -> Found {
        println!("cargo:rerun-if-env-changed=PETSC_DIR");
        println!("cargo:rerun-if-env-changed=PETSC_ARCH");
        if let Ok(dir) = std::env::var("PETSC_DIR") {
            let dir = PathBuf::from(dir);
            let arch = std::env::var("PETSC_ARCH").ok().map(|a| dir.join(a));
            let mut include = vec![dir.join("include")];
            let mut libs = vec![dir.join("lib")];
            if let Some(a) = arch {
                include.push(a.join("include"));
                libs.push(a.join("lib"));
            }
            for l in &libs {
                println!("cargo:rustc-link-search=native={}", l.display());
            }
            let name = if libs.iter().any(|l| l.join("libpetsc_real.so").exists()) {
                "petsc_real"
            } else {
                "petsc"
            };
            println!("cargo:rustc-link-lib={name}");
            return Found { include, libs };
        }
        match pkg_config::Config::new().probe("PETSc") {
            Ok(lib) => Found {
                include: lib.include_paths,
                libs: lib.link_paths,
            },
            Err(e) => panic!(
                "the `petsc` feature needs the system PETSc: run `bash petsc/install.sh` \
                 (Debian libpetsc-real-dev) or set PETSC_DIR; pkg-config said: {e}"
            ),
        }
    }

    /// MPI include directories (PETSc's headers include `mpi.h`).
    fn mpi_includes() -> Vec<PathBuf> {
        for name in ["ompi-c", "mpich", "mpi"] {
            if let Ok(lib) = pkg_config::Config::new().cargo_metadata(false).probe(name) {
                return lib.include_paths;
            }
        }
        Vec::new()
    }

    /// `#define PETSC_HAVE_<NAME> 1` in `petscconf.h`.
    fn has_package(include: &[PathBuf], name: &str) -> bool {
        let needle = format!("#define PETSC_HAVE_{name} 1");
        include.iter().any(|d| {
            std::fs::read_to_string(d.join("petscconf.h"))
                .map(|t| t.lines().any(|l| l.trim() == needle))
                .unwrap_or(false)
        })
    }

    pub fn generate() {
        println!("cargo:rerun-if-changed=wrapper.h");
        let petsc = find_petsc();
        let _ = &petsc.libs;
        println!("cargo:rustc-link-lib=metis");
        if has_package(&petsc.include, "HYPRE") {
            println!("cargo:rustc-cfg=petsc_have_hypre");
        }
        if has_package(&petsc.include, "MUMPS") {
            println!("cargo:rustc-cfg=petsc_have_mumps");
        }
        let mut builder = bindgen::builder().header("wrapper.h");
        for dir in petsc.include.iter().chain(mpi_includes().iter()) {
            builder = builder.clang_arg(format!("-I{}", dir.display()));
        }
        let bindings = builder
            .allowlist_function("(Petsc|Mat|Vec|KSP|PC|IS)[A-Za-z]*")
            .allowlist_function("METIS_[A-Za-z]*")
            .allowlist_var("PETSC_COMM_WORLD|PETSC_DECIDE|PETSC_DETERMINE|PETSC_DEFAULT")
            .allowlist_var("(MAT|KSP|PC)[A-Z0-9_]*|METIS_[A-Z_]*")
            .allowlist_type("(Petsc|Mat|Vec|KSP|PC|Insert|Norm|ScatterMode)[A-Za-z]*")
            .allowlist_type("(rstatus|moptions)_et|idx_t|real_t")
            .new_type_alias("MPI_Comm")
            .derive_default(true)
            .layout_tests(false)
            .generate_comments(false)
            .generate()
            .expect("bindgen could not read the PETSc headers (libclang-dev installed?)");
        let out = PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR"));
        bindings
            .write_to_file(Path::new(&out).join("bindings.rs"))
            .expect("write bindings.rs");
    }
}
