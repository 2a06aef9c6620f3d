scene.material "m" { base_color_map = "s_not_a.png" }
scene.sphere "b" { material = "m" }
