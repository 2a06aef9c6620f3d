scene.light "l" { type = "point", intensity = 100, unit = "lux" }
