# Speed against accuracy (issue 6): the tradeoff sweep, its chart and the accuracy picker.
