//! Links the dbrg C library: from DBRG_LIB_DIR when set, else as pkg-config describes it.
//! DBRG_STATIC=1 links libdbrg.a (and the C++ runtime) instead of the shared library.

use std::env;
use std::path::Path;
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-env-changed=DBRG_LIB_DIR");
    println!("cargo:rerun-if-env-changed=DBRG_STATIC");
    println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
    let link_static = env::var("DBRG_STATIC").map(|v| v == "1").unwrap_or(false);

    if let Some(dir) = env::var_os("DBRG_LIB_DIR") {
        let dir = Path::new(&dir);
        let file = if link_static { "libdbrg.a" } else { "libdbrg.so" };
        if !dir.join(file).exists() && !dir.join("libdbrg.dylib").exists() && !dir.join("dbrg.lib").exists() {
            panic!(
                "DBRG_LIB_DIR is {}, but it holds no {}; point it at the directory of the built library \
                 (for a meson build: build/src)",
                dir.display(),
                file
            );
        }
        println!("cargo:rustc-link-search=native={}", dir.display());
        link_dbrg(link_static);
        // Lets this crate's own tests and examples run from a build tree without LD_LIBRARY_PATH.
        if !link_static && cfg!(unix) {
            println!("cargo:rustc-link-arg=-Wl,-rpath,{}", dir.display());
        }
        return;
    }

    let mut pkg_config = Command::new(env::var("PKG_CONFIG").unwrap_or_else(|_| "pkg-config".to_string()));
    pkg_config.arg("--libs");
    if link_static {
        pkg_config.arg("--static");
    }
    match pkg_config.arg("dbrg").output() {
        Ok(output) if output.status.success() => {
            let flags = String::from_utf8_lossy(&output.stdout).into_owned();
            for flag in flags.split_whitespace() {
                if let Some(dir) = flag.strip_prefix("-L") {
                    println!("cargo:rustc-link-search=native={}", dir);
                } else if let Some(name) = flag.strip_prefix("-l") {
                    if name == "dbrg" {
                        link_dbrg(link_static);
                    } else {
                        println!("cargo:rustc-link-lib={}", name);
                    }
                }
            }
        }
        _ => panic!(
            "cannot find the dbrg C library. Build it (meson setup build && ninja -C build) and set \
             DBRG_LIB_DIR to the directory holding libdbrg.so (e.g. DBRG_LIB_DIR=$PWD/build/src), or install \
             it (meson install) so that `pkg-config --libs dbrg` finds it. Set DBRG_STATIC=1 to link libdbrg.a."
        ),
    }
}

fn link_dbrg(link_static: bool) {
    if link_static {
        // The static library is C++ inside: it needs the C++ runtime and threads.
        println!("cargo:rustc-link-lib=static=dbrg");
        println!("cargo:rustc-link-lib=dylib=stdc++");
        println!("cargo:rustc-link-lib=dylib=pthread");
    } else {
        println!("cargo:rustc-link-lib=dylib=dbrg");
    }
}
