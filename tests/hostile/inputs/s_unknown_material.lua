scene.sphere "ball" { material = "nope" }
