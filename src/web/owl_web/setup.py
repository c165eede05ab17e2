from setuptools import find_packages, setup

package_name = 'owl_web'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    package_data={package_name: ['static/*']},
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
    ],
    install_requires=['setuptools'],
    zip_safe=False,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='Server layer of the browser pages: static files, npm libraries, JSON API, WebSocket.',
    license='Apache-2.0',
    tests_require=['pytest'],
)
