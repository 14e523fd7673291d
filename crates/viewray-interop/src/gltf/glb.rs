//! The `.glb` container: a 12-byte header (`glTF`, version 2, total length), then a JSON
//! chunk and an optional binary chunk, each an 8-byte header (length, type) and its
//! bytes, little-endian.

use std::path::Path;

use crate::ImportError;

/// The first four bytes of a `.glb`.
pub(super) const MAGIC: &[u8; 4] = b"glTF";
/// The type of the JSON chunk, `JSON` in ASCII.
const CHUNK_JSON: u32 = 0x4E4F_534A;
/// The type of the binary chunk, `BIN\0` in ASCII.
const CHUNK_BIN: u32 = 0x004E_4942;

/// A `.glb` of the JSON `document` and the binary chunk `buffer`, if any (already
/// padded to a multiple of 4 bytes). The JSON is padded with spaces.
pub(super) fn write(document: &serde_json::Value, buffer: Option<&[u8]>) -> Vec<u8> {
    let mut json_bytes = serde_json::to_vec(document).expect("JSON values serialize");
    while !json_bytes.len().is_multiple_of(4) {
        json_bytes.push(b' ');
    }
    let total = 12 + 8 + json_bytes.len() + buffer.map_or(0, |b| 8 + b.len());
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&u32::try_from(total).unwrap_or(u32::MAX).to_le_bytes());
    out.extend_from_slice(
        &u32::try_from(json_bytes.len())
            .unwrap_or(u32::MAX)
            .to_le_bytes(),
    );
    out.extend_from_slice(&CHUNK_JSON.to_le_bytes());
    out.extend_from_slice(&json_bytes);
    if let Some(buffer) = buffer {
        out.extend_from_slice(
            &u32::try_from(buffer.len())
                .unwrap_or(u32::MAX)
                .to_le_bytes(),
        );
        out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        out.extend_from_slice(buffer);
    }
    out
}

/// The JSON and the binary chunk of a `.glb`, or the JSON of a `.gltf`.
pub(super) fn split<'a>(
    bytes: &'a [u8],
    path: &Path,
) -> Result<(&'a [u8], Option<&'a [u8]>), ImportError> {
    if !bytes.starts_with(MAGIC) {
        return Ok((bytes, None));
    }
    let error = |m: &str| ImportError::new(path, None, format!("not a valid .glb: {m}"));
    let word = |at: usize| -> Option<u32> {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes(b.try_into().expect("4 bytes")))
    };
    if word(4) != Some(2) {
        return Err(error("only glTF 2 binaries are read"));
    }
    let mut at = 12;
    let mut json = None;
    let mut bin = None;
    while at + 8 <= bytes.len() {
        let length = word(at).ok_or_else(|| error("truncated chunk header"))? as usize;
        let kind = word(at + 4).ok_or_else(|| error("truncated chunk header"))?;
        let data = bytes
            .get(at + 8..at + 8 + length)
            .ok_or_else(|| error("a chunk runs past the end of the file"))?;
        match kind {
            CHUNK_JSON if json.is_none() => json = Some(data),
            CHUNK_BIN if bin.is_none() => bin = Some(data),
            _ => {}
        }
        at += 8 + length;
    }
    Ok((json.ok_or_else(|| error("no JSON chunk"))?, bin))
}
