//! Repair: valid solids from imperfect soups.

mod broken_fixtures;
mod random;
