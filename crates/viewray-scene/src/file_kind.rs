//! What kind of file viewray is given, told from its first bytes and its name: the one
//! place where viewray recognises its inputs, so that a command given the wrong kind of
//! file can say what the file is.

use std::path::Path;

/// A kind of file viewray reads, writes or is likely to be handed by mistake.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FileKind {
    /// A viewray scene file (RON).
    Scene,
    /// A Wavefront OBJ mesh.
    ObjMesh,
    /// A Wavefront MTL material library, an OBJ mesh's materials.
    ObjMaterials,
    /// A Mitsuba 3 scene (XML).
    MitsubaXml,
    /// A pbrt-v4 scene.
    Pbrt,
    /// A Blender Python script (the `bpy` module), as viewray's Blender export writes.
    BlenderScript,
    /// A three.js JSON object (`object.toJSON()`).
    ThreeJson,
    /// A glTF 2.0 scene as JSON (`.gltf`).
    Gltf,
    /// A glTF 2.0 scene in binary (`.glb`).
    Glb,
    /// A PNG image.
    Png,
    /// A PPM image (netpbm `P3` or `P6`).
    Ppm,
    /// An OpenEXR image.
    Exr,
}

/// The PNG signature.
const PNG_MAGIC: &[u8] = b"\x89PNG\r\n\x1a\n";
/// The OpenEXR magic number, 20000630 little-endian.
const EXR_MAGIC: &[u8] = &[0x76, 0x2f, 0x31, 0x01];
/// The binary glTF magic.
const GLB_MAGIC: &[u8] = b"glTF";

/// OBJ statements a mesh file starts with (after its comments).
const OBJ_STATEMENTS: [&str; 12] = [
    "v", "vt", "vn", "vp", "f", "l", "p", "o", "g", "s", "mtllib", "usemtl",
];

/// pbrt-v4 directives a scene file starts with (after its comments).
const PBRT_DIRECTIVES: [&str; 20] = [
    "LookAt",
    "Camera",
    "Film",
    "Sampler",
    "Integrator",
    "WorldBegin",
    "Scale",
    "Translate",
    "Rotate",
    "Transform",
    "ConcatTransform",
    "Option",
    "ColorSpace",
    "PixelFilter",
    "Identity",
    "CoordinateSystem",
    "AttributeBegin",
    "Import",
    "Include",
    "LightSource",
];

impl FileKind {
    /// Every kind, scene first.
    pub const ALL: [FileKind; 12] = [
        FileKind::Scene,
        FileKind::ObjMesh,
        FileKind::ObjMaterials,
        FileKind::MitsubaXml,
        FileKind::Pbrt,
        FileKind::BlenderScript,
        FileKind::ThreeJson,
        FileKind::Gltf,
        FileKind::Glb,
        FileKind::Png,
        FileKind::Ppm,
        FileKind::Exr,
    ];

    /// What the file is, for a sentence: "an OBJ mesh", "a PNG image".
    pub fn description(self) -> &'static str {
        match self {
            FileKind::Scene => "a viewray scene file",
            FileKind::ObjMesh => "an OBJ mesh",
            FileKind::ObjMaterials => "an MTL material library",
            FileKind::MitsubaXml => "a Mitsuba 3 scene (XML)",
            FileKind::Pbrt => "a pbrt-v4 scene",
            FileKind::BlenderScript => "a Blender Python script",
            FileKind::ThreeJson => "a three.js JSON object",
            FileKind::Gltf => "a glTF scene",
            FileKind::Glb => "a binary glTF scene",
            FileKind::Png => "a PNG image",
            FileKind::Ppm => "a PPM image",
            FileKind::Exr => "an OpenEXR image",
        }
    }

    /// The kind of the file `path` holding `bytes` (the whole file), if it is one viewray
    /// knows.
    ///
    /// In order: an image's or a binary glTF's signature; text that starts as a scene
    /// file does, `(` or `#![` after any whitespace and comments; the extension (`.ron`,
    /// `.obj`, `.mtl`, `.xml`, `.pbrt`, `.py` with `bpy` in it, `.json` (glTF when it
    /// has an `asset` with a `version`, else three.js), `.gltf`, `.glb`, `.png`, `.ppm`,
    /// `.exr`); and failing those, the text itself: `<` is XML, `{` JSON, a line
    /// importing `bpy` a Blender script, and the first statement after the `#` comments
    /// an OBJ mesh's, an MTL library's (`newmtl`) or a pbrt scene's.
    pub fn recognise(path: &Path, bytes: &[u8]) -> Option<FileKind> {
        if let Some(kind) = by_signature(bytes) {
            return Some(kind);
        }
        let text = std::str::from_utf8(bytes).ok();
        let start = text.map(|text| text.trim_start_matches('\u{feff}').trim_start());
        if start.is_some_and(starts_like_a_scene) {
            return Some(FileKind::Scene);
        }
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let by_extension = match extension.as_deref() {
            Some("ron") => Some(FileKind::Scene),
            Some("obj") => Some(FileKind::ObjMesh),
            Some("mtl") => Some(FileKind::ObjMaterials),
            Some("xml") => Some(FileKind::MitsubaXml),
            Some("pbrt") => Some(FileKind::Pbrt),
            Some("py") if text.is_some_and(imports_bpy) => Some(FileKind::BlenderScript),
            Some("json") => Some(json_kind(bytes)),
            Some("gltf") => Some(FileKind::Gltf),
            Some("glb") => Some(FileKind::Glb),
            Some("png") => Some(FileKind::Png),
            Some("ppm") => Some(FileKind::Ppm),
            Some("exr") => Some(FileKind::Exr),
            _ => None,
        };
        by_extension.or_else(|| by_content(text?, start?, bytes))
    }

    /// Why a file of this kind is not a scene file, and where it goes instead, as a
    /// sentence that follows the file's name (`cube.obj: this is an OBJ mesh; a scene file
    /// names it in `objects``); `None` for a scene file.
    pub fn not_a_scene(self) -> Option<String> {
        Some(match self {
            FileKind::Scene => return None,
            FileKind::ObjMesh => {
                "this is an OBJ mesh; a scene file names it in `objects`".to_owned()
            }
            FileKind::ObjMaterials => "this is an MTL material library; the OBJ mesh that uses it \
                                       names it (`mtllib`), and a scene file names the mesh in \
                                       `objects`"
                .to_owned(),
            other => format!("this is {}, not a viewray scene file", other.description()),
        })
    }
}

/// The kinds a file's first bytes say for sure.
fn by_signature(bytes: &[u8]) -> Option<FileKind> {
    if bytes.starts_with(PNG_MAGIC) {
        Some(FileKind::Png)
    } else if bytes.starts_with(EXR_MAGIC) {
        Some(FileKind::Exr)
    } else if bytes.starts_with(GLB_MAGIC) {
        Some(FileKind::Glb)
    } else if (bytes.starts_with(b"P3") || bytes.starts_with(b"P6"))
        && bytes.get(2).is_some_and(u8::is_ascii_whitespace)
    {
        Some(FileKind::Ppm)
    } else {
        None
    }
}

/// Whether text (from its first non-blank character) starts as a scene file does: a
/// value in parentheses, or a RON attribute, after any `//` and `/* */` comments.
fn starts_like_a_scene(start: &str) -> bool {
    let value = skip_whitespace_and_comments(start);
    value.starts_with('(') || value.starts_with("#![")
}

/// Whether a Python script imports Blender's `bpy` module.
fn imports_bpy(text: &str) -> bool {
    text.lines().any(|line| {
        let line = line.trim_start();
        line.starts_with("import bpy") || line.starts_with("from bpy")
    })
}

/// A JSON file: glTF when it is JSON with an `asset` that has a `version`, else three.js.
fn json_kind(bytes: &[u8]) -> FileKind {
    let is_gltf = serde_json::from_slice::<serde_json::Value>(bytes)
        .ok()
        .is_some_and(|json| json.pointer("/asset/version").is_some());
    if is_gltf {
        FileKind::Gltf
    } else {
        FileKind::ThreeJson
    }
}

/// The kind of a text file with no telling extension, from its text (`start` is its
/// text from the first non-blank character).
fn by_content(text: &str, start: &str, bytes: &[u8]) -> Option<FileKind> {
    if start.starts_with('<') {
        return Some(FileKind::MitsubaXml);
    }
    if start.starts_with('{') {
        return Some(json_kind(bytes));
    }
    if imports_bpy(text) {
        return Some(FileKind::BlenderScript);
    }
    // The first statement after the blank and `#` comment lines.
    let first = text
        .lines()
        .map(str::trim)
        .find(|line| !line.is_empty() && !line.starts_with('#'))?
        .split_whitespace()
        .next()?;
    if OBJ_STATEMENTS.contains(&first) {
        Some(FileKind::ObjMesh)
    } else if first == "newmtl" {
        Some(FileKind::ObjMaterials)
    } else if PBRT_DIRECTIVES.contains(&first) {
        Some(FileKind::Pbrt)
    } else {
        None
    }
}

/// `text` from its first character that is neither whitespace nor in a RON comment
/// (`//` to the end of the line, `/* .. */`): where a scene file's value starts.
pub(crate) fn skip_whitespace_and_comments(mut text: &str) -> &str {
    loop {
        let trimmed = text.trim_start();
        if let Some(rest) = trimmed.strip_prefix("//") {
            text = rest.split_once('\n').map_or("", |(_, after)| after);
        } else if let Some(rest) = trimmed.strip_prefix("/*") {
            text = rest.split_once("*/").map_or("", |(_, after)| after);
        } else {
            return trimmed;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check(name: &str, text: &[u8], expected: Option<FileKind>) {
        assert_eq!(
            FileKind::recognise(Path::new(name), text),
            expected,
            "{name}"
        );
    }

    #[test]
    fn signatures_win_over_names() {
        check("a.ron", b"\x89PNG\r\n\x1a\n....", Some(FileKind::Png));
        check("a", &[0x76, 0x2f, 0x31, 0x01, 2, 0], Some(FileKind::Exr));
        check("a.json", b"glTF\x02\0\0\0", Some(FileKind::Glb));
        check("a", b"P6\n4 4\n255\n", Some(FileKind::Ppm));
        check("a", b"P3 1 1 255 0 0 0", Some(FileKind::Ppm));
        check("a", b"P7\n", None);
    }

    #[test]
    fn scene_text_is_a_scene_whatever_its_name() {
        check(
            "a.json",
            b"(camera: Front(target: (0.0, 0.0, 0.0), size: 2.0))",
            Some(FileKind::Scene),
        );
        check(
            "a.xml",
            b"\xef\xbb\xbf // a comment\n/* and another */ (camera: ..)",
            Some(FileKind::Scene),
        );
        check(
            "a",
            b"#![enable(implicit_some)]\n(camera: ..)",
            Some(FileKind::Scene),
        );
        check("a.ron", b"camera: oops", Some(FileKind::Scene));
        check("a.ron", b"\xff\xfe not text", Some(FileKind::Scene));
    }

    #[test]
    fn extensions_name_the_rest() {
        let cases = [
            ("cube.obj", FileKind::ObjMesh),
            ("cube.MTL", FileKind::ObjMaterials),
            ("s.xml", FileKind::MitsubaXml),
            ("s.pbrt", FileKind::Pbrt),
            ("s.gltf", FileKind::Gltf),
            ("s.glb", FileKind::Glb),
            ("p.png", FileKind::Png),
            ("p.ppm", FileKind::Ppm),
            ("p.exr", FileKind::Exr),
        ];
        for (name, kind) in cases {
            check(name, b"whatever", Some(kind));
        }
        check(
            "s.json",
            br#"{"asset": {"version": "2.0"}}"#,
            Some(FileKind::Gltf),
        );
        check(
            "s.json",
            br#"{"metadata": {"version": 4.6}}"#,
            Some(FileKind::ThreeJson),
        );
        check(
            "s.json",
            br#"{"asset": {"version": "2.0"}"#,
            Some(FileKind::ThreeJson),
        );
        check(
            "model.blender.py",
            b"# Written by viewray\nimport bpy\n",
            Some(FileKind::BlenderScript),
        );
        check("tool.py", b"import os\n", None);
    }

    #[test]
    fn text_without_a_telling_name_is_read() {
        check(
            "s",
            b"  <scene version=\"3.0.0\"/>",
            Some(FileKind::MitsubaXml),
        );
        check(
            "s",
            br#"{"asset": {"version": "2.0"}}"#,
            Some(FileKind::Gltf),
        );
        check("s", b"{}", Some(FileKind::ThreeJson));
        check(
            "s",
            b"# made by hand\nfrom bpy import data\n",
            Some(FileKind::BlenderScript),
        );
        check(
            "s",
            b"# a cube\n\nmtllib cube.mtl\nv 0 0 0\n",
            Some(FileKind::ObjMesh),
        );
        check("s", b"v 0 0 0\nf 1 2 3\n", Some(FileKind::ObjMesh));
        check(
            "s",
            b"# colours\nnewmtl red\nKd 1 0 0\n",
            Some(FileKind::ObjMaterials),
        );
        check(
            "s",
            b"# pbrt\nLookAt 0 0 5  0 0 0  0 1 0\n",
            Some(FileKind::Pbrt),
        );
        check("s", b"Film \"rgb\"\n", Some(FileKind::Pbrt));
        check("s", b"# only a comment\n", None);
        check("s", b"hello", None);
        check("s", b"", None);
        check("s", b"\xff\xfe", None);
    }

    #[test]
    fn every_kind_says_what_it_is_and_why_it_is_not_a_scene() {
        for kind in FileKind::ALL {
            let description = kind.description();
            assert!(
                description.starts_with("a ") || description.starts_with("an "),
                "{kind:?}"
            );
            match kind.not_a_scene() {
                None => assert_eq!(kind, FileKind::Scene),
                Some(message) => assert!(message.starts_with("this is "), "{message}"),
            }
        }
        assert_eq!(
            FileKind::ObjMesh.not_a_scene().unwrap(),
            "this is an OBJ mesh; a scene file names it in `objects`"
        );
        assert_eq!(
            FileKind::Png.not_a_scene().unwrap(),
            "this is a PNG image, not a viewray scene file"
        );
    }
}
