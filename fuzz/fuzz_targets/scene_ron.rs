//! Any text given as a scene file loads or fails with one clear error, never a panic,
//! a hang or unbounded memory.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    // Meshes resolve against a folder that does not exist, so no file is read.
    let path = Path::new("/nonexistent-viewray-fuzz/scene.ron");
    if let Err(error) = viewray_scene::SceneLoader::text(text, path).load() {
        let message = error.to_string();
        assert!(!message.contains('\n'), "error is not one line: {message}");
    }
});
