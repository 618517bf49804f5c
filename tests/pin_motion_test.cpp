// Tests of the pin_motion module (being written).
