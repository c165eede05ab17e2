"""A student's pygame key reader as section 4.4.1's project reads the keyboard: a window, events in a loop.

Prints each arrow key's KEYDOWN/KEYUP and, from pygame.key.get_pressed(), when the set of held
arrows changes; at Ctrl-C how many loops it ran.
"""

import time

import pygame

ARROWS = {pygame.K_LEFT: 'left', pygame.K_RIGHT: 'right', pygame.K_UP: 'up', pygame.K_DOWN: 'down'}

pygame.init()
screen = pygame.display.set_mode((200, 80))
pygame.display.set_caption('keys')
held = set()
loops = 0
try:
    while True:
        for event in pygame.event.get():
            if event.type in (pygame.KEYDOWN, pygame.KEYUP) and event.key in ARROWS:
                kind = 'down' if event.type == pygame.KEYDOWN else 'up'
                print(f'{kind} {ARROWS[event.key]}', flush=True)
        pressed = pygame.key.get_pressed()
        now = {name for key, name in ARROWS.items() if pressed[key]}
        if now != held:
            held = now
            print(f"held: {' '.join(sorted(held)) or 'none'}", flush=True)
        screen.fill((0, 128, 0) if held else (128, 0, 0))
        pygame.display.flip()
        loops += 1
        time.sleep(0.01)
except KeyboardInterrupt:
    pass
finally:
    pygame.quit()
print(f'ran {loops} loops', flush=True)
