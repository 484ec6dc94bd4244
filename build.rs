//! Links the command-line program as a position-dependent executable on Linux: its start then
//! applies no relocations. As a position-independent one it applied 15,600 at every start, and
//! wrote each page of its tables of addresses (about 80 pages of its own), a fifth of the time
//! `flexrock --version` takes. The libraries (the core, the Python module) are not affected.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let linux = std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux");
    let gnu = std::env::var("CARGO_CFG_TARGET_ENV").as_deref() == Ok("gnu");
    if linux && gnu {
        println!("cargo:rustc-link-arg-bins=-no-pie");
    }
}
