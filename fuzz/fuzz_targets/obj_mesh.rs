//! Any bytes given as an OBJ mesh load or fail with a message, never a panic, a hang or
//! unbounded memory.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    if let Err(message) = viewray_scene::fuzz_parse_obj(bytes) {
        assert!(!message.contains('\n'), "error is not one line: {message}");
    }
});
