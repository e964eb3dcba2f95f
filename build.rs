//! Compiles the lalrpop grammars in `grammar/` into parsers under OUT_DIR.
fn main() {
    lalrpop::Configuration::new()
        .set_in_dir("grammar")
        .process()
        .expect("lalrpop grammar compilation failed");
    println!("cargo:rerun-if-changed=grammar");
}
