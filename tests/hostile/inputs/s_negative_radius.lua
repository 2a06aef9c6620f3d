scene.sphere "ball" { radius = -1 }
