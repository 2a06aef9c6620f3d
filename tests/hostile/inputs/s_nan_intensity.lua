scene.light "l" { type = "point", intensity = 0/0, unit = "lm" }
