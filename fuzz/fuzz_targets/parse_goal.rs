//! Any text: the .goal and .mod2g parsers never panic and every span lies in the text.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(src) = std::str::from_utf8(data) else {
        return;
    };
    let (_, diags) = goal::syntax::goal::parse_goal("fuzz.goal", src);
    for d in &diags {
        assert!(d.span.start <= d.span.end && d.span.end <= src.len());
    }
    let (_, diags) = goal::syntax::goal::parse_mod2g("fuzz.mod2g", src);
    for d in &diags {
        assert!(d.span.end <= src.len());
    }
});
