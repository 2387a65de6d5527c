//! The built-in scenes, as data (`data/presets.json`, scene files like any user's). The AFM
//! geometry and lattice spacing are those of the classic AFM example (a 20 nm tip on a 0.25 nm
//! lattice); the material values are representative handbook values, stated as such in each
//! scene's `source`.

use super::SceneInput;
use std::sync::OnceLock;

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Preset {
    preset: String,
    scene: SceneInput,
}

fn all() -> &'static [Preset] {
    static PRESETS: OnceLock<Vec<Preset>> = OnceLock::new();
    PRESETS.get_or_init(|| {
        serde_json::from_str(include_str!("../../data/presets.json"))
            .expect("data/presets.json is a list of scenes (checked by the tests)")
    })
}

/// A built-in scene by name.
pub fn preset(name: &str) -> Option<SceneInput> {
    all()
        .iter()
        .find(|p| p.preset == name)
        .map(|p| p.scene.clone())
}

/// The built-in scenes' names, in the order of `data/presets.json`.
pub fn preset_names() -> Vec<&'static str> {
    all().iter().map(|p| p.preset.as_str()).collect()
}
