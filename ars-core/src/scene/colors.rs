//! The original's named colours (W3C), as RGB in [0, 1]. The original divided by 256
//! (so its white was 0.996); these divide by 255.

use super::Color;

const fn rgb(r: u8, g: u8, b: u8) -> Color {
    [r as f32 / 255.0, g as f32 / 255.0, b as f32 / 255.0]
}

/// Black.
pub const BLACK: Color = rgb(0, 0, 0);
/// Blue.
pub const BLUE: Color = rgb(0, 0, 255);
/// Brown.
pub const BROWN: Color = rgb(165, 42, 42);
/// Cyan.
pub const CYAN: Color = rgb(0, 255, 255);
/// Gold.
pub const GOLD: Color = rgb(255, 215, 0);
/// Gray.
pub const GRAY: Color = rgb(128, 128, 128);
/// Green (W3C: dark).
pub const GREEN: Color = rgb(0, 128, 0);
/// Lime (bright green).
pub const LIME: Color = rgb(0, 255, 0);
/// Lime green.
pub const LIME_GREEN: Color = rgb(50, 205, 50);
/// Maroon.
pub const MAROON: Color = rgb(128, 0, 0);
/// Magenta.
pub const MAGENTA: Color = rgb(255, 0, 255);
/// Navy.
pub const NAVY: Color = rgb(0, 0, 128);
/// Olive.
pub const OLIVE: Color = rgb(128, 128, 0);
/// Orange.
pub const ORANGE: Color = rgb(255, 165, 0);
/// Pink.
pub const PINK: Color = rgb(255, 192, 203);
/// Purple.
pub const PURPLE: Color = rgb(128, 0, 128);
/// Red.
pub const RED: Color = rgb(255, 0, 0);
/// Silver.
pub const SILVER: Color = rgb(192, 192, 192);
/// Snow.
pub const SNOW: Color = rgb(255, 250, 250);
/// Violet.
pub const VIOLET: Color = rgb(238, 130, 238);
/// Yellow.
pub const YELLOW: Color = rgb(255, 255, 0);
/// White.
pub const WHITE: Color = rgb(255, 255, 255);
