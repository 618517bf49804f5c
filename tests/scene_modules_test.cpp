// Tests of the scene_modules module (being written).
