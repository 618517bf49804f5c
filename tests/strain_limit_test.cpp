// Tests of the strain_limit module (being written).
