// Tests of the colliders module (being written).
