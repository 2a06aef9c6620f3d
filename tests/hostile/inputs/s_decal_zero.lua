scene.decal "d" { size = { 0, 1, 1 } }
