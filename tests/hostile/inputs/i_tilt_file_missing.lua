scene.light "l" { type = "point", intensity = 1000, unit = "lm", position = { 0, 2, 0 }, ies = "i_tilt_file_missing.ies" }
