//! Any bytes given as a three.js JSON object import or fail with one clear error, never a panic, a
//! hang or unbounded memory; what imports is a scene file viewray reads back.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;
use viewray_interop::Format;

fuzz_target!(|bytes: &[u8]| {
    // Relative mesh files resolve against a folder that does not exist.
    let path = Path::new("/nonexistent-viewray-fuzz/scene.json");
    match viewray_interop::import(bytes, path, Format::Three) {
        Err(error) => {
            let message = error.to_string();
            assert!(!message.contains('\n'), "error is not one line: {message}");
        }
        Ok(document) => {
            // The whole document writes; its camera loads or is refused in one line, as
            // `viewray import` checks it.
            let _ = document.to_ron();
            let camera_only = viewray_scene::SceneDocument {
                objects: Vec::new(),
                ..document
            };
            if let Err(error) = viewray_scene::SceneLoader::text(&camera_only.to_ron(), path).load()
            {
                let message = error.to_string();
                assert!(!message.contains('\n'), "error is not one line: {message}");
            }
        }
    }
});
