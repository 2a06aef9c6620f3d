scene.sphere "ball" { segments = 1e9 }
