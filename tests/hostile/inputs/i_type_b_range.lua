scene.light "l" { type = "point", intensity = 1000, unit = "lm", position = { 0, 2, 0 }, ies = "i_type_b_range.ies" }
