//! Links the `urdf_validate` binary as a position-dependent executable on Linux (`-no-pie`).
//!
//! A position-independent executable has tens of thousands of relocations that the dynamic loader applies
//! at every start, writing (and so copying) every page of `.data.rel.ro`: on a virtual machine where a
//! page fault is expensive that was about a third of the time of a short run. Linked at a fixed address,
//! those relocations are resolved by the linker once. The library crates, the Python extension and the
//! tests are not affected (only the binaries get the flag).

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let os = std::env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let env = std::env::var("CARGO_CFG_TARGET_ENV").unwrap_or_default();
    if os == "linux" && (env == "gnu" || env == "musl") {
        println!("cargo:rustc-link-arg-bins=-no-pie");
    }
}
