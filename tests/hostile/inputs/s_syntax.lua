scene.sphere "a" {
