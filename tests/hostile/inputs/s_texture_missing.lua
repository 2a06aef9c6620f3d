scene.material "m" { base_color_map = "nope.png" }
scene.sphere "b" { material = "m" }
