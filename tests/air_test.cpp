// Tests of the air module (being written).
