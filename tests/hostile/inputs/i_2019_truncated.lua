scene.light "l" { type = "point", intensity = 1000, unit = "lm", position = { 0, 2, 0 }, ies = "i_2019_truncated.ies" }
