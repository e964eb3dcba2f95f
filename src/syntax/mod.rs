//! The syntax layer: the `logos` lexer, the `lalrpop` grammars (in `grammar/`), the AST with byte
//! spans for `.goal`, `.mas2g`, `.test2g` and `.pl` files, and the validator.
pub mod ast;
pub mod check;
pub mod codes;
pub mod goal;
pub mod lexer;
pub mod mas2g;
pub mod modular;
pub mod prolog;
pub mod test2g;
pub mod validate;
