// Tests of the self_collision module (being written).
