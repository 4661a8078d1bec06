//! Links the dbrg C library and its I/O library (libdbrg_io): each from a directory named in the
//! environment when set, else as pkg-config describes it.
//!
//! libdbrg: DBRG_LIB_DIR, else `pkg-config dbrg`. libdbrg_io: DBRG_IO_LIB_DIR, else DBRG_LIB_DIR when it
//! holds libdbrg_io too (an installed libdir) or DBRG_LIB_DIR/io (a meson build tree), else
//! `pkg-config dbrg_io`. DBRG_STATIC=1 links libdbrg.a (and the C++ runtime) instead of libdbrg.so;
//! libdbrg_io is always the shared library, since no static archive of its C interface is installed.

use std::env;
use std::path::{Path, PathBuf};
use std::process::Command;

/// One of the two libraries and how to find it.
struct Library {
    name: &'static str,
    link_static: bool,
}

impl Library {
    fn file_names(&self) -> Vec<String> {
        if self.link_static {
            vec![format!("lib{}.a", self.name)]
        } else {
            vec![format!("lib{}.so", self.name), format!("lib{}.dylib", self.name), format!("{}.lib", self.name)]
        }
    }

    fn is_in(&self, dir: &Path) -> bool {
        self.file_names().iter().any(|file| dir.join(file).exists())
    }
}

fn main() {
    for variable in ["DBRG_LIB_DIR", "DBRG_IO_LIB_DIR", "DBRG_STATIC", "PKG_CONFIG_PATH"] {
        println!("cargo:rerun-if-env-changed={}", variable);
    }
    let link_static = env::var("DBRG_STATIC").map(|v| v == "1").unwrap_or(false);
    let dbrg = Library { name: "dbrg", link_static };
    let dbrg_io = Library { name: "dbrg_io", link_static: false };

    let lib_dir = env::var_os("DBRG_LIB_DIR").map(PathBuf::from);
    match &lib_dir {
        Some(dir) => link_from_dir(&dbrg, dir, "DBRG_LIB_DIR", "for a meson build: build/src"),
        None => link_with_pkg_config(&dbrg),
    }
    match (env::var_os("DBRG_IO_LIB_DIR").map(PathBuf::from), lib_dir) {
        (Some(dir), _) => link_from_dir(&dbrg_io, &dir, "DBRG_IO_LIB_DIR", "for a meson build: build/src/io"),
        (None, Some(dir)) => {
            let io_dir = if dbrg_io.is_in(&dir) { dir.clone() } else { dir.join("io") };
            if !dbrg_io.is_in(&io_dir) {
                panic!(
                    "DBRG_LIB_DIR is {}, but neither it nor its io/ folder holds libdbrg_io.so; set \
                     DBRG_IO_LIB_DIR to the directory of the built I/O library (for a meson build: build/src/io)",
                    dir.display()
                );
            }
            link_from_dir(&dbrg_io, &io_dir, "DBRG_IO_LIB_DIR", "for a meson build: build/src/io");
        }
        (None, None) => link_with_pkg_config(&dbrg_io),
    }
}

fn link_from_dir(library: &Library, dir: &Path, variable: &str, hint: &str) {
    if !library.is_in(dir) {
        panic!(
            "{} is {}, but it holds no {}; point it at the directory of the built library ({})",
            variable,
            dir.display(),
            library.file_names()[0],
            hint
        );
    }
    println!("cargo:rustc-link-search=native={}", dir.display());
    link(library);
    // Lets this crate's own tests and examples run from a build tree without LD_LIBRARY_PATH.
    if !library.link_static && cfg!(unix) {
        println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
    }
}

fn link_with_pkg_config(library: &Library) {
    let mut pkg_config = Command::new(env::var("PKG_CONFIG").unwrap_or_else(|_| "pkg-config".to_string()));
    pkg_config.arg("--libs");
    if library.link_static {
        pkg_config.arg("--static");
    }
    match pkg_config.arg(library.name).output() {
        Ok(output) if output.status.success() => {
            let flags = String::from_utf8_lossy(&output.stdout).into_owned();
            for flag in flags.split_whitespace() {
                if let Some(dir) = flag.strip_prefix("-L") {
                    println!("cargo:rustc-link-search=native={}", dir);
                } else if let Some(name) = flag.strip_prefix("-l") {
                    if name == library.name {
                        link(library);
                    } else {
                        println!("cargo:rustc-link-lib={}", name);
                    }
                }
            }
        }
        _ => panic!(
            "cannot find lib{name}. Build dbrg (meson setup build && ninja -C build) and set DBRG_LIB_DIR to \
             the directory holding libdbrg.so (e.g. DBRG_LIB_DIR=$PWD/build/src; libdbrg_io is then found in \
             its io/ folder, or set DBRG_IO_LIB_DIR), or install dbrg (meson install) so that \
             `pkg-config --libs {name}` finds it. Set DBRG_STATIC=1 to link libdbrg.a.",
            name = library.name
        ),
    }
}

fn link(library: &Library) {
    if library.link_static {
        // The static library is C++ inside: it needs the C++ runtime and threads.
        println!("cargo:rustc-link-lib=static={}", library.name);
        println!("cargo:rustc-link-lib=dylib=stdc++");
        println!("cargo:rustc-link-lib=dylib=pthread");
    } else {
        println!("cargo:rustc-link-lib=dylib={}", library.name);
    }
}
